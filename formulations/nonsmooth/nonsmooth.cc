// Placeholder while the formulations of this folder are written (issue 3).
#include "formulations/nonsmooth/nonsmooth.h"

#include <stdexcept>

namespace cb {
std::unique_ptr<Formulation> MakeNonsmoothFb(const FormulationConfig&) {
  throw std::logic_error("nonsmooth-fb: not written yet");
}
std::unique_ptr<Formulation> MakeActiveSet(const FormulationConfig&) {
  throw std::logic_error("active-set: not written yet");
}

}  // namespace cb
