#include "formulations/common/start_solvers.h"

namespace cb {

bool TakesNonmonotoneSearch(const StartPoint& start) {
  return start.kind == StartKind::kCold || start.across_contact_change;
}

SolverOptions SolverOptionsFor(const StartPoint& start, const SolverOptions& options) {
  SolverOptions chosen = options;
  if (!TakesNonmonotoneSearch(start)) chosen.nonmonotone_window = 1;
  return chosen;
}

StartSolvers::StartSolvers(const std::string& solver, const SolverOptions& options)
    : nonmonotone_(MakeEquationSolver(solver, options)), monotone_([&] {
        SolverOptions monotone = options;
        monotone.nonmonotone_window = 1;
        return MakeEquationSolver(solver, monotone);
      }()) {}

EquationSolver& StartSolvers::For(const StartPoint& start) const {
  return TakesNonmonotoneSearch(start) ? *nonmonotone_ : *monotone_;
}

}  // namespace cb
