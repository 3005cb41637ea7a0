// Names -> formulations, for the harness and the benchmarks.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "formulations/common/config.h"
#include "step/formulation.h"

namespace cb {

struct FormulationInfo {
  std::string name;
  std::string description;
  bool available = true;  // its dependency was built
  std::unique_ptr<Formulation> (*make)(const FormulationConfig&) = nullptr;
};

// In a fixed order: implicit-fb first.
const std::vector<FormulationInfo>& FormulationRegistry();
std::vector<std::string> FormulationNames();
// Throws std::invalid_argument for an unknown name (listing the valid ones), a formulation
// not built into this binary, or bad settings.
std::unique_ptr<Formulation> MakeFormulation(const std::string& name,
                                             const FormulationConfig& config);

}  // namespace cb
