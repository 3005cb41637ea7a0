// Names -> formulations, for the harness and the benchmarks.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solvers/equation_solver.h"
#include "step/formulation.h"

namespace cb {

// Settings a formulation may use (each documents which it reads).
struct FormulationConfig {
  std::string solver = "newton";  // equation solver (implicit-fb)
  int eta = 1;                    // eta case 1..4 (implicit-fb)
  SolverOptions solver_options;
};

struct FormulationInfo {
  std::string name;
  std::string description;
  bool available = true;
};

std::vector<FormulationInfo> FormulationRegistry();
std::vector<std::string> FormulationNames();
// Throws std::invalid_argument for an unknown name (listing the valid ones) or bad settings.
std::unique_ptr<Formulation> MakeFormulation(const std::string& name,
                                             const FormulationConfig& config);

}  // namespace cb
