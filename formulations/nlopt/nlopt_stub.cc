// What the registry finds when NLopt was not found at configure time (nlopt.cmake builds this
// file instead of the adapter and the formulations). The options are still read, so that a bad
// option is reported as such in every build.
#include <stdexcept>

#include "formulations/nlopt/nlopt.h"
#include "formulations/nlopt/nlopt_options.h"

namespace cb {

bool NloptAvailable() { return false; }
std::string NloptVersion() { return ""; }

std::unique_ptr<Formulation> MakeNloptMerit(const FormulationConfig& config) {
  ReadNloptMeritOptions(config);
  throw std::invalid_argument("nlopt-merit: NLopt was not found when this build was configured");
}

std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig& config) {
  ReadNloptEnergyOptions(config);
  throw std::invalid_argument("nlopt-energy: NLopt was not found when this build was configured");
}

std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig& config) {
  ReadNloptMpccOptions(config);
  throw std::invalid_argument("nlopt-mpcc: NLopt was not found when this build was configured");
}

}  // namespace cb
