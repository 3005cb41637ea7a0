// What the registry finds when Siconos numerics was not found at configure time (siconos.cmake
// builds this file instead of the adapter and the formulations).
#include <stdexcept>

#include "formulations/siconos/siconos.h"

namespace cb {

bool SiconosAvailable() { return false; }
std::string SiconosVersion() { return ""; }

std::unique_ptr<Formulation> MakeSiconosLemke(const FormulationConfig&) {
  throw std::invalid_argument("siconos-lemke: this build has no Siconos numerics");
}

std::unique_ptr<Formulation> MakeSiconosNewtonFb(const FormulationConfig&) {
  throw std::invalid_argument("siconos-newton-fb: this build has no Siconos numerics");
}

std::unique_ptr<Formulation> MakeSiconosNewtonMin(const FormulationConfig&) {
  throw std::invalid_argument("siconos-newton-min: this build has no Siconos numerics");
}

}  // namespace cb
