// What the registry finds when Ipopt was not found at configure time (ipopt.cmake builds this
// file instead of the adapter and the formulations).
#include <stdexcept>

#include "formulations/ipopt/ipopt.h"

namespace cb {

bool IpoptAvailable() { return false; }
std::string IpoptVersion() { return ""; }

std::unique_ptr<Formulation> MakeIpoptEnergy(const FormulationConfig&) {
  throw std::invalid_argument("ipopt-energy: this build has no Ipopt");
}

std::unique_ptr<Formulation> MakeIpoptMpcc(const FormulationConfig&) {
  throw std::invalid_argument("ipopt-mpcc: this build has no Ipopt");
}

}  // namespace cb
