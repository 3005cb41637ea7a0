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

// A library the suite is linked with and its version ("" when this build has none of it).
struct LinkedLibrary {
  std::string name;
  std::string version;
};
// Every library built in whose version can change an answer or a time: the core's (Eigen,
// SuiteSparse) and each backend's; run.json records them beside the BLAS the process runs on
// (core/blas_info.h: chosen when the process starts, not at build time).
std::vector<LinkedLibrary> LinkedLibraries();
// Throws std::invalid_argument for an unknown name (listing the valid ones), a formulation
// not built into this binary, or bad settings.
std::unique_ptr<Formulation> MakeFormulation(const std::string& name,
                                             const FormulationConfig& config);

}  // namespace cb
