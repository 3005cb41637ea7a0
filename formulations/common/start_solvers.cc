#include "formulations/common/start_solvers.h"

namespace cb {

SolverOptions SolverOptionsFor(StartKind kind, const SolverOptions& options) {
  SolverOptions chosen = options;
  if (kind != StartKind::kCold) chosen.nonmonotone_window = 1;
  return chosen;
}

StartSolvers::StartSolvers(const std::string& solver, const SolverOptions& options)
    : cold_(MakeEquationSolver(solver, SolverOptionsFor(StartKind::kCold, options))),
      warm_(MakeEquationSolver(solver, SolverOptionsFor(StartKind::kWarm, options))) {}

EquationSolver& StartSolvers::For(StartKind kind) const {
  return kind == StartKind::kCold ? *cold_ : *warm_;
}

}  // namespace cb
