// The bookkeeping of a solve of the step equations: the history, the controls and the result
// (step_equations.h, RunStepEquationSolver).
#include <algorithm>
#include <cmath>
#include <string>

#include "core/timer.h"
#include "formulations/common/step_equations.h"
#include "step/time_limit.h"

namespace cb {

double ComplementarityResidual(const StepEquationLayout& l, const Vec& x) {
  double comp = 0.0;
  for (int p = 0; p < l.nc; ++p)
    comp = std::max(comp, std::abs(std::min(x[l.g() + p], -x[l.r() + p])));
  return comp;
}

SolverSummary RunStepEquationSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                    const SolveControls& controls, StepResult* result,
                                    const std::function<void(const Vec&)>& on_iteration) {
  const StepEquationLayout& l = system.layout();
  const StepProblem& step = system.step();
  Stopwatch clock;
  bool timed_out = false;
  auto observe = [&](const IterationInfo& info) {
    IterationRecord record;
    record.iteration = info.iteration;
    record.merit = info.merit;
    record.residual_inf = info.residual_inf;
    record.step_length = info.step_length;
    record.comp_res = ComplementarityResidual(l, *info.x);
    result->history.push_back(record);
    if (on_iteration) on_iteration(*info.x);
    if (controls.interrupted && controls.interrupted()) return false;
    timed_out = PastTimeLimit(controls, clock);
    return !timed_out;
  };
  SolverSummary summary = solver.Solve(system, x, observe);  // not const: returned by move
  if (timed_out && summary.status == Status::kStoppedByCaller) {
    summary.status = Status::kTimeLimit;
    summary.message = TimeLimitMessage(controls.time_limit_s) + " at iteration " +
                      std::to_string(summary.iterations);
  }

  result->status = summary.status;
  result->message = summary.message;
  result->counts = {summary.iterations, summary.residual_evals, summary.jacobian_evals,
                    summary.linear_solves};
  result->point = PointFromScaled(step, l, *x);
  result->details["final_merit"] = std::to_string(summary.final_merit);
  return summary;
}

}  // namespace cb
