#include "path/near_start.h"

#include <cmath>

namespace cb {

State PerturbedSolution(const State& solution, double delta) {
  State near = solution;
  for (int i = 0; i < near.u.size(); ++i) near.u[i] *= 1.0 + delta * std::sin(i + 1.0);
  for (int i = 0; i < near.r.size(); ++i) near.r[i] *= 1.0 + delta * std::sin(i + 2.0);
  return near;
}

bool NearSolutionStart(const ContactModel& model, const ContactScales& scales, const State& initial,
                       double lambda, Formulation& reference, const PathOptions& options,
                       double delta, State* start, std::string* why) {
  const PathSummary solved =
      SolveFixedLoad(model, scales, initial, lambda, reference, options, nullptr);
  if (solved.status != Status::kConverged) {
    *why = solved.message;
    return false;
  }
  *start = PerturbedSolution(solved.final_state, delta);
  return true;
}

}  // namespace cb
