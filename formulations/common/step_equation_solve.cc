// The bookkeeping of a solve of the step equations: the history, the controls and the result
// (step_equations.h, StepSolveBookkeeping and RunStepEquationSolver).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "formulations/common/step_equations.h"
#include "step/time_limit.h"

namespace cb {

double ComplementarityResidual(const StepEquationLayout& l, const Vec& x) {
  double comp = 0.0;
  for (int p = 0; p < l.nc; ++p)
    comp = std::max(comp, std::abs(std::min(x[l.g() + p], -x[l.r() + p])));
  return comp;
}

IterationCallback StepSolveBookkeeping::Observer(std::function<double(const Vec&)> comp_res,
                                                 std::function<void(const Vec&)> on_iteration) {
  return [this, comp_res = std::move(comp_res),
          on_iteration = std::move(on_iteration)](const IterationInfo& info) {
    IterationRecord record;
    record.iteration = info.iteration;
    record.merit = info.merit;
    record.residual_inf = info.residual_inf;
    record.step_length = info.step_length;
    record.comp_res = comp_res(*info.x);
    result_->history.push_back(record);
    if (on_iteration) on_iteration(*info.x);
    if (controls_.interrupted && controls_.interrupted()) return false;
    timed_out_ = PastTimeLimit(controls_, clock_);
    return !timed_out_;
  };
}

void StepSolveBookkeeping::MarkTimeLimit(SolverSummary* summary) const {
  if (!timed_out_ || summary->status != Status::kStoppedByCaller) return;
  summary->status = Status::kTimeLimit;
  summary->message = TimeLimitMessage(controls_.time_limit_s) + " at iteration " +
                     std::to_string(summary->iterations);
}

void StepSolveBookkeeping::FillResult(const StepEquationSystem& system, const Vec& x,
                                      const SolverSummary& summary) const {
  result_->status = summary.status;
  result_->message = summary.message;
  result_->counts = {summary.iterations, summary.residual_evals, summary.jacobian_evals,
                     summary.linear_solves};
  result_->point = PointFromScaled(system.step(), system.layout(), x);
  result_->details["final_merit"] = std::to_string(summary.final_merit);
}

SolverSummary RunStepEquationSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                    const SolveControls& controls, StepResult* result,
                                    const std::function<void(const Vec&)>& on_iteration) {
  const StepEquationLayout& l = system.layout();
  StepSolveBookkeeping bookkeeping(controls, result);
  auto comp_res = [&l](const Vec& iterate) { return ComplementarityResidual(l, iterate); };
  SolverSummary summary =  // not const: returned by move
      solver.Solve(system, x, bookkeeping.Observer(comp_res, on_iteration));
  bookkeeping.MarkTimeLimit(&summary);
  bookkeeping.FillResult(system, *x, summary);
  return summary;
}

}  // namespace cb
