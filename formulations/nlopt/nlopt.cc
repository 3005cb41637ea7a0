// Placeholder while the formulations of this folder are written (issue 3).
#include "formulations/nlopt/nlopt.h"

#include <stdexcept>

namespace cb {

bool NloptAvailable() { return false; }
std::unique_ptr<Formulation> MakeNloptMerit(const FormulationConfig&) {
  throw std::logic_error("nlopt-merit: not written yet");
}
std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig&) {
  throw std::logic_error("nlopt-energy: not written yet");
}
std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig&) {
  throw std::logic_error("nlopt-mpcc: not written yet");
}
}  // namespace cb
