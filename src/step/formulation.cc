#include "step/formulation.h"

#include <stdexcept>

#include "core/timer.h"

namespace cb {

const char* ToString(StartKind kind) { return kind == StartKind::kWarm ? "warm" : "cold"; }

StepResult Formulation::Solve(const StepProblem& step, const StartPoint& start,
                              const SolveControls& controls) {
  step.Validate();
  if (!available()) throw std::invalid_argument(name() + ": not available in this build");
  if (!Supports(step.constraint.kind)) {
    throw std::invalid_argument(name() + " cannot express the step constraint '" +
                                std::string(ToString(step.constraint.kind)) + "'");
  }
  const int d = step.num_dofs();
  const int nc = step.num_pairs();
  if (start.kind == StartKind::kWarm) {
    if (start.du.size() != d) throw std::invalid_argument("start.du has the wrong size");
    if (start.r.size() != nc) throw std::invalid_argument("start.r has the wrong size");
  }
  StepResult result;
  Stopwatch clock;
  DoSolve(step, start, controls, &result);
  result.time_s = clock.Seconds();
  if (result.point.du.size() != d || result.point.g.size() != nc || result.point.r.size() != nc) {
    throw std::logic_error(name() + " returned a point of the wrong size");
  }
  return result;
}

}  // namespace cb
