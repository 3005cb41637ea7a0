// The bookkeeping of a solve through the reduced system (reduced_step_system.h,
// RunReducedStepSolver): as RunStepEquationSolver, with the iterates z = (du_c, g^, r^[, rho])
// and the full answer recovered once at the end.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/timer.h"
#include "formulations/common/reduced_step_system.h"
#include "step/time_limit.h"

namespace cb {
namespace {

// ||min(g^, -r^)||_inf over the pairs of z (g^ from `first_g`).
double ReducedComplementarityResidual(const Vec& z, int first_g, int nc) {
  double comp = 0.0;
  for (int p = 0; p < nc; ++p)
    comp = std::max(comp, std::abs(std::min(z[first_g + p], -z[first_g + nc + p])));
  return comp;
}

}  // namespace

SolverSummary RunReducedStepSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                   const SolveControls& controls, StepResult* result) {
  const StepEquationLayout& l = system.layout();
  const StepProblem& step = system.step();
  ReducedStepSystem reduced(system);
  Stopwatch clock;
  SolverSummary summary;
  result->details["reduced_newton"] = std::to_string(1);
  if (!reduced.Prepare(*x)) {
    summary.status = Status::kFailed;
    summary.message = "reduced Newton: the interior stiffness A_ii is not positive definite";
    result->status = summary.status;
    result->message = summary.message;
    result->point = PointFromScaled(step, l, *x);
    return summary;
  }
  const int first_g = reduced.num_contact_dofs();
  Vec z = reduced.Reduce(*x);
  bool timed_out = false;
  auto observe = [&](const IterationInfo& info) {
    IterationRecord record;
    record.iteration = info.iteration;
    record.merit = info.merit;
    record.residual_inf = info.residual_inf;
    record.step_length = info.step_length;
    record.comp_res = ReducedComplementarityResidual(*info.x, first_g, l.nc);
    result->history.push_back(record);
    if (controls.interrupted && controls.interrupted()) return false;
    timed_out = PastTimeLimit(controls, clock);
    return !timed_out;
  };
  summary = solver.Solve(reduced, &z, observe);
  if (timed_out && summary.status == Status::kStoppedByCaller) {
    summary.status = Status::kTimeLimit;
    summary.message = TimeLimitMessage(controls.time_limit_s) + " at iteration " +
                      std::to_string(summary.iterations);
  }
  if (!reduced.Expand(z, x) && summary.status == Status::kConverged) {
    summary.status = Status::kFailed;
    summary.message = "reduced Newton: the interior could not be recovered";
  }
  result->status = summary.status;
  result->message = summary.message;
  result->counts = {summary.iterations, summary.residual_evals, summary.jacobian_evals,
                    summary.linear_solves};
  result->point = PointFromScaled(step, l, *x);
  result->details["final_merit"] = std::to_string(summary.final_merit);
  result->details["interior_by_contact_block"] =
      std::to_string(reduced.elimination().uses_contact_block() ? 1 : 0);
  return summary;
}

}  // namespace cb
