#pragma once

#include <memory>
#include <string>

#include "solvers/equation_solver.h"
#include "step/formulation.h"

namespace cb {

// The equation solvers of one formulation, one for each start kind. A cold start gets the
// options as given, with the nonmonotone line search of SolverOptions::nonmonotone_window that
// takes P1's cold solves through the stretch where the full Newton step raises the merit. A warm
// start is near its answer, so it keeps the monotone test (window 1): its 2-3 iterations per
// step are unchanged, and so is every warm path that depends on its last digits, such as P2's
// branch switch at C (docs/findings.md).
// The options of the solver for a start of `kind` (see StartSolvers), from the formulation's.
SolverOptions SolverOptionsFor(StartKind kind, const SolverOptions& options);

class StartSolvers {
 public:
  StartSolvers(const std::string& solver, const SolverOptions& options);
  EquationSolver& For(StartKind kind) const;

 private:
  std::unique_ptr<EquationSolver> cold_;
  std::unique_ptr<EquationSolver> warm_;
};

}  // namespace cb
