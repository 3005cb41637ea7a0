// The square system (29)-(33) of the implicit smoothed Fischer-Burmeister formulation for one
// step: the shared rows of common/step_equations.h in the unknowns x = (du, g^, r^, dlambda,
// rho), with the complementarity rows psi (31) and the eta row (32) added here:
//   F3_p = psi(g^_p, -r^_p, rho)                                       (31),       nc rows
//          (for the pair of a kink step, g^_p + r^_p: see StepEquationSystem::Residual)
//   F4 = eta equation (32) divided by nc (EtaEquation),                           1 row.
#pragma once

#include <memory>
#include <vector>

#include "formulations/common/step_equations.h"
#include "formulations/implicit_fb/eta_equation.h"

namespace cb {

class ImplicitFbSystem final : public StepEquationSystem {
 public:
  // The Jacobian pattern (StepEquationSystem::PatternCache), built on first use and reusable by
  // later systems of the same model, constraint kind and index (a path analyses it once).
  using PatternCache = StepEquationSystem::PatternCache;

  ImplicitFbSystem(const StepProblem& step, EtaEquation eta,
                   std::shared_ptr<PatternCache> cache = nullptr);
  ~ImplicitFbSystem() override;

  const EtaEquation& eta() const { return eta_; }

 private:
  // (31): psi(g^_p, -r^_p, rho), with the generalised-Jacobian element of
  // FischerBurmeisterElement where it is not differentiable (rho = 0, case 4).
  double Complementarity(double a, double b, double rho) const override;
  void ComplementarityElement(double a, double b, double rho, double* d_a, double* d_b,
                              double* d_rho) const override;
  // (32) / nc.
  double ExtraRow(const Vec& x) const override;
  void AppendExtraRowEntries(std::vector<ScatterPattern::Entry>* entries) const override;
  void FillExtraRow(const Vec& x, Cursor* cursor) const override;

  EtaEquation eta_;
};

}  // namespace cb
