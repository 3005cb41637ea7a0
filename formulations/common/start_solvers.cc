#include "formulations/common/start_solvers.h"

namespace cb {

namespace {

SolverOptions Monotone(SolverOptions options) {
  options.nonmonotone_window = 1;
  return options;
}

}  // namespace

StartSolvers::StartSolvers(const std::string& solver, const SolverOptions& options)
    : cold_(MakeEquationSolver(solver, options)),
      warm_(MakeEquationSolver(solver, Monotone(options))) {}

EquationSolver& StartSolvers::For(StartKind kind) const {
  return kind == StartKind::kCold ? *cold_ : *warm_;
}

}  // namespace cb
