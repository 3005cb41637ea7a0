#include "formulations/nonsmooth/nonsmooth.h"

namespace cb {

NonsmoothSystem::NonsmoothSystem(const StepProblem& step, ComplementarityFunction function,
                                 std::shared_ptr<PatternCache> cache)
    : StepEquationSystem(step, /*has_rho=*/false, std::move(cache)), function_(function) {}

NonsmoothSystem::~NonsmoothSystem() = default;

double NonsmoothSystem::Complementarity(double a, double b, double /*rho*/) const {
  return function_ == ComplementarityFunction::kMin ? MinFunction(a, b)
                                                    : SmoothedFischerBurmeister(a, b, 0.0);
}

void NonsmoothSystem::ComplementarityElement(double a, double b, double /*rho*/, double* d_a,
                                             double* d_b, double* d_rho) const {
  *d_rho = 0.0;
  if (function_ == ComplementarityFunction::kMin) {
    if (a == b) ++nonsmooth_elements_;
    MinElement(a, b, d_a, d_b);
    return;
  }
  if (a == 0.0 && b == 0.0) ++nonsmooth_elements_;
  double unused = 0.0;
  FischerBurmeisterElement(a, b, 0.0, d_a, d_b, &unused);
}

}  // namespace cb
