// Names -> formulations, for the harness and the benchmarks.
#pragma once

#include <functional>
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
  std::function<std::unique_ptr<Formulation>(const FormulationConfig&)> make;
  // Its step is solved over the processes of an MPI run (formulations/petsc_dist): the serial
  // benchmarks and the one-process comparisons leave it out.
  bool distributed = false;
  // It takes the backend option `petsc_options` (the CLI's --petsc-options).
  bool takes_petsc_options = false;
};

// In a fixed order: implicit-fb first, the built-in ones, then those registered at run time in
// the order of registration.
const std::vector<FormulationInfo>& FormulationRegistry();

// Adds a formulation made outside the suite's tree (a Python callable, docs/your-own-method.md)
// to the registry, after the built-in ones: from then on it is named, listed, made and run like
// them. Throws std::invalid_argument for an empty name, a name with characters other than
// letters, digits, '-', '_' and '.', a name already registered, or no factory. Not thread-safe:
// register before a run starts (references into the registry stay valid only until the next
// registration).
void RegisterFormulation(FormulationInfo info);
std::vector<std::string> FormulationNames();
// The registry's entry of `name`; nullptr for a name it does not know.
const FormulationInfo* FindFormulation(const std::string& name);
// Whether `name` is a known formulation that takes `petsc_options` (its registry entry says).
bool TakesPetscOptions(const std::string& name);

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
