// nonsmooth-fb: the nonsmooth step equations with the plain Fischer-Burmeister function ((12)
// with rho = 0, common/step_equations.h), solved by semismooth Newton (see nonsmooth.h).
#include "formulations/nonsmooth/nonsmooth.h"

namespace cb {

std::unique_ptr<Formulation> MakeNonsmoothFb(const FormulationConfig& config) {
  return MakeNonsmooth(ComplementarityFunction::kFischerBurmeister, config);
}

}  // namespace cb
