#include "step/formulation.h"

#include <sstream>
#include <stdexcept>

#include "core/timer.h"

namespace cb {

const char* ToString(StartKind kind) { return kind == StartKind::kWarm ? "warm" : "cold"; }

std::string TimeLimitMessage(double time_limit_s) {
  std::ostringstream text;
  text << "time limit of " << time_limit_s << " s reached";
  return text.str();
}

bool Formulation::Accepts(const StepProblem& step, std::string* why) const {
  std::string reason;
  if (DoAccepts(step, &reason)) return true;
  if (why != nullptr) *why = reason;
  return false;
}

StepResult Formulation::Solve(const StepProblem& step, const StartPoint& start,
                              const SolveControls& controls) {
  step.Validate();
  std::string why;
  if (!Accepts(step, &why)) throw std::invalid_argument(why);
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
  result.time_min_s = result.time_max_s = result.time_s;
  result.time_samples = 1;
  if (result.point.du.size() != d || result.point.g.size() != nc || result.point.r.size() != nc) {
    throw std::logic_error(name() + " returned a point of the wrong size");
  }
  return result;
}

}  // namespace cb
