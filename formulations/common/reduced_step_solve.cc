// The bookkeeping of a solve through the reduced system (reduced_step_system.h,
// RunReducedStepSolver): as RunStepEquationSolver, with the iterates z = (du_c, g^, r^[, rho])
// and the full answer recovered once at the end.
#include <algorithm>
#include <cmath>
#include <string>

#include "formulations/common/reduced_step_system.h"

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
  ReducedStepSystem reduced(system);
  StepSolveBookkeeping bookkeeping(controls, result);
  SolverSummary summary;
  result->details["reduced_newton"] = std::to_string(1);
  if (!reduced.Prepare(*x)) {
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
  summary = solver.Solve(reduced, &z, bookkeeping.Observer(comp_res));
  bookkeeping.MarkTimeLimit(&summary);
  if (!reduced.Expand(z, x) && summary.status == Status::kConverged) {
    summary.status = Status::kFailed;
    summary.message = "reduced Newton: the interior could not be recovered";
  }
  bookkeeping.FillResult(system, *x, summary);
  result->details["interior_by_contact_block"] =
      std::to_string(reduced.elimination().uses_contact_block() ? 1 : 0);
  return summary;
}

}  // namespace cb
