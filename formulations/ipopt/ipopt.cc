// Placeholder while the formulations of this folder are written (issue 3).
#include "formulations/ipopt/ipopt.h"

#include <stdexcept>

namespace cb {

bool IpoptAvailable() { return false; }
std::unique_ptr<Formulation> MakeIpoptEnergy(const FormulationConfig&) {
  throw std::logic_error("ipopt-energy: not written yet");
}
std::unique_ptr<Formulation> MakeIpoptMpcc(const FormulationConfig&) {
  throw std::logic_error("ipopt-mpcc: not written yet");
}

}  // namespace cb
