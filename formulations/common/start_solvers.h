#pragma once

#include <memory>
#include <string>

#include "solvers/equation_solver.h"
#include "step/formulation.h"

namespace cb {

// The equation solvers of one formulation: one with the options as given, with the nonmonotone
// line search of SolverOptions::nonmonotone_window, and one with the monotone test (window 1).
// The nonmonotone one takes the starts that are far from their answer through the stretch where
// the full Newton step raises the merit: cold starts (P1's cold solves), and warm starts across a
// contact change (StartPoint::across_contact_change), whose answer lies just past a corner of
// the path (P3's steps that crept for up to 50 iterations; docs/findings.md). Every other warm
// start is near its answer and keeps the monotone test: its 2-3 iterations per step are
// unchanged, and so is every warm path that depends on its last digits, such as P2's branch
// switch at C.
bool TakesNonmonotoneSearch(const StartPoint& start);
// The options of the solver for `start` (see above), from the formulation's.
SolverOptions SolverOptionsFor(const StartPoint& start, const SolverOptions& options);

class StartSolvers {
 public:
  StartSolvers(const std::string& solver, const SolverOptions& options);
  EquationSolver& For(const StartPoint& start) const;

 private:
  std::unique_ptr<EquationSolver> nonmonotone_;
  std::unique_ptr<EquationSolver> monotone_;
};

}  // namespace cb
