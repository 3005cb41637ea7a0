#include "formulations/registry.h"

#include <stdexcept>

#include "formulations/implicit_fb/implicit_fb.h"

namespace cb {

std::vector<FormulationInfo> FormulationRegistry() {
  return {
      {"implicit-fb",
       "implicit smoothed Fischer-Burmeister equations (29)-(33), rho an unknown; eta cases 1-4",
       true},
  };
}

std::vector<std::string> FormulationNames() {
  std::vector<std::string> names;
  for (const auto& info : FormulationRegistry()) names.push_back(info.name);
  return names;
}

std::unique_ptr<Formulation> MakeFormulation(const std::string& name,
                                             const FormulationConfig& config) {
  if (name == "implicit-fb") {
    if (config.eta < 1 || config.eta > 4) {
      throw std::invalid_argument("eta must be 1, 2, 3 or 4 (got " + std::to_string(config.eta) +
                                  ")");
    }
    ImplicitFbOptions options;
    options.eta = static_cast<EtaCase>(config.eta);
    options.solver = config.solver;
    options.solver_options = config.solver_options;
    return std::make_unique<ImplicitFb>(options);
  }
  std::string valid;
  for (const auto& n : FormulationNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown formulation '" + name + "' (valid: " + valid + ")");
}

}  // namespace cb
