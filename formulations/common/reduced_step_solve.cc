// The bookkeeping of a solve through the reduced system (reduced_step_system.h,
// RunReducedStepSolver): as RunStepEquationSolver, with the iterates z = (du_c, g^, r^[, rho])
// and the full answer recovered once at the end.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/timer.h"
#include "formulations/common/reduced_step_system.h"
#include "solvers/solver_common.h"

namespace cb {
namespace {

// ||min(g^, -r^)||_inf over the pairs of z (g^ from `first_g`).
double ReducedComplementarityResidual(const Vec& z, int first_g, int nc) {
  double comp = 0.0;
  for (int p = 0; p < nc; ++p)
    comp = std::max(comp, std::abs(std::min(z[first_g + p], -z[first_g + nc + p])));
  return comp;
}

std::string Seconds(double s) { return std::to_string(s); }

// Whether every full row of `system` at x is within max(residual_tol, its rounding floor).
bool FullRowsHold(StepEquationSystem& system, const Vec& x, double residual_tol) {
  Vec f, floor;
  if (!system.Residual(x, &f)) return false;
  const bool has_floor = system.ResidualFloor(x, &floor);
  return internal::WithinResidualFloor(f, has_floor ? &floor : nullptr, residual_tol);
}

SolveCounts operator+(const SolveCounts& a, const SolveCounts& b) {
  return {a.iterations + b.iterations, a.residual_evals + b.residual_evals,
          a.jacobian_evals + b.jacobian_evals, a.linear_solves + b.linear_solves};
}

}  // namespace

SolverSummary RunReducedStepSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                   const SolveControls& controls, StepResult* result) {
  const StepEquationLayout& l = system.layout();
  ReducedStepSystem reduced(system);
  StepSolveBookkeeping bookkeeping(controls, result);
  SolverSummary summary;
  result->details["route"] = "reduced";
  Stopwatch prepare;
  const bool prepared = reduced.Prepare(*x);
  result->details["prepare_s"] = Seconds(prepare.Seconds());
  if (!prepared) {
    const bool interrupted = reduced.elimination().interrupted();
    summary.status = interrupted ? Status::kStoppedByCaller : Status::kFailed;
    summary.message = interrupted
                          ? "reduced Newton: the factorisation of A + D0 abandoned on an interrupt"
                          : "reduced Newton: the interior stiffness A_ii is not positive definite";
    result->status = summary.status;
    result->message = summary.message;
    result->point = PointFromScaled(system.step(), l, *x);
    return summary;
  }
  const int first_g = reduced.num_contact_dofs();
  auto comp_res = [first_g, nc = l.nc](const Vec& z) {
    return ReducedComplementarityResidual(z, first_g, nc);
  };
  Vec z = reduced.Reduce(*x);
  Stopwatch iterations;
  summary = solver.Solve(reduced, &z, bookkeeping.Observer(comp_res));
  result->details["iterations_s"] = Seconds(iterations.Seconds());
  bookkeeping.MarkTimeLimit(&summary);
  Stopwatch recovery;
  if (!reduced.Expand(z, x) && summary.status == Status::kConverged) {
    summary.status = Status::kFailed;
    summary.message = "reduced Newton: the interior could not be recovered";
  }
  result->details["recovery_s"] = Seconds(recovery.Seconds());
  const ReducedStepTimes& times = reduced.times();
  result->details["factorization_s"] = Seconds(times.factorization_s);
  result->details["forward_sweep_s"] = Seconds(times.forward_sweep_s);
  result->details["backward_sweep_s"] = Seconds(times.backward_sweep_s);
  bookkeeping.FillResult(system, *x, summary);
  result->details["interior_by_contact_block"] =
      std::to_string(reduced.elimination().uses_contact_block() ? 1 : 0);
  return summary;
}

SolverSummary RunReducedOrFullStepSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                         const SolveControls& controls, double residual_tol,
                                         StepResult* result) {
  const Vec start = *x;
  const Stopwatch clock;
  SolverSummary reduced = RunReducedStepSolver(solver, system, x, controls, result);
  if (reduced.status == Status::kStoppedByCaller || reduced.status == Status::kTimeLimit) {
    return reduced;
  }
  const bool holds = reduced.status == Status::kConverged && FullRowsHold(system, *x, residual_tol);
  if (holds) return reduced;
  const std::string why = reduced.status == Status::kConverged
                              ? "its answer leaves full rows above the tolerance"
                              : reduced.message;
  const SolveCounts spent = result->counts;
  const std::size_t reduced_history = result->history.size();
  SolveControls rest = controls;
  if (rest.time_limit_s > 0.0)
    rest.time_limit_s = std::max(1e-3, rest.time_limit_s - clock.Seconds());
  *x = start;
  SolverSummary full = RunStepEquationSolver(solver, system, x, rest, result);
  result->counts = result->counts + spent;
  // The full route's iterations numbered on from the reduced ones, so that the step's history
  // (iterations.csv) counts as its counts do.
  for (std::size_t k = reduced_history; k < result->history.size(); ++k) {
    result->history[k].iteration += spent.iterations;
  }
  result->message += " (the full route, after the reduced Newton: " + why + ")";
  result->details["route"] = "full after reduced";
  return full;
}

}  // namespace cb
