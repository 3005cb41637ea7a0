// active-set: the nonsmooth step equations with min(g^, -r^) = 0, solved by semismooth Newton
// (the primal-dual active set method; see nonsmooth.h).
#include "formulations/nonsmooth/nonsmooth.h"

namespace cb {

double MinFunction(double a, double b) { return a < b ? a : b; }

void MinElement(double a, double b, double* d_a, double* d_b) {
  // a <= b: the pair is active, the row reads g^ = 0 (ties included, see the header);
  // otherwise r^ = 0.
  *d_a = a <= b ? 1.0 : 0.0;
  *d_b = a <= b ? 0.0 : 1.0;
}

std::unique_ptr<Formulation> MakeActiveSet(const FormulationConfig& config) {
  return MakeNonsmooth(ComplementarityFunction::kMin, config);
}

}  // namespace cb
