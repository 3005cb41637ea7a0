#include "formulations/nonsmooth/nonsmooth_restart.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <vector>

namespace cb {

bool TakesRestart(const NonsmoothOptions& options, const SolverSummary& summary,
                  const StepProblem& step, const StartPoint& start) {
  const StepConstraint& c = step.constraint;
  return options.restart && summary.status != Status::kConverged &&
         summary.status != Status::kStoppedByCaller && summary.status != Status::kTimeLimit &&
         !(summary.final_residual_inf <= options.restart_residual) &&
         start.kind == StartKind::kWarm && c.kind == ConstraintKind::kArcLength &&
         c.lambda_weight > 0.0;
}

StartPoint RestartPoint(const StepProblem& step, const StartPoint& start, int nc) {
  // Back along the predictor to the first contact, then turn.
  const StepConstraint& c = step.constraint;
  StartPoint again = start;
  const Vec& u = step.base.u;
  Vec phi;
  step.model->Gaps(u, &phi);
  const double floor = std::min(nc > 0 ? (-phi).minCoeff() : 0.0, 0.0);
  auto opens = [&](double t) {
    step.model->Gaps(u + t * start.du, &phi);
    return nc == 0 || (-phi).minCoeff() >= floor;
  };
  double t = 1.0;
  if (!opens(1.0)) {
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      (opens(mid) ? lo : hi) = mid;
    }
    t = lo;
  }
  again.du = t * start.du;
  const double rest = c.arc_length * c.arc_length - again.du.squaredNorm();
  again.dlambda =
      (start.dlambda > 0.0 ? -1.0 : 1.0) * std::sqrt(std::max(rest, 0.0)) / c.lambda_weight;
  return again;
}

void LeanOnClosedPairs(const StepProblem& step, const StartPoint& again,
                       const StepEquationLayout& l, Vec* x) {
  // The start leans on the contact it has just met instead of sitting at the degenerate
  // g = r = 0 (from where Newton returns to the free branch).
  std::vector<int> closed;
  for (int p = 0; p < l.nc; ++p) {
    if ((*x)[l.g() + p] <= 1e-8) closed.push_back(p);
  }
  if (closed.empty()) return;
  const Vec u0 = step.base.u + again.du;
  Vec out_of_balance;
  step.model->InternalForce(u0, &out_of_balance);
  out_of_balance -= (step.base.lambda + again.dlambda) * step.model->load_pattern();
  SpMat gap_jacobian;
  step.model->GapJacobian(u0, &gap_jacobian);
  const int k = static_cast<int>(closed.size());
  std::vector<Triplet> pick;
  pick.reserve(k);
  for (int j = 0; j < k; ++j) pick.emplace_back(j, closed[j], 1.0);
  SpMat select(k, l.nc);
  select.setFromTriplets(pick.begin(), pick.end());
  const SpMat gc = select * gap_jacobian;  // the closed pairs' rows, k x d, sparse
  // The normal matrix is only k x k (pairs closed), so a dense factorisation is cheap.
  const Mat normal = Mat(SpMat(gc * gc.transpose()));
  const Vec rc = normal.ldlt().solve(gc * out_of_balance);
  for (int j = 0; j < k; ++j) {
    if (std::isfinite(rc[j])) (*x)[l.r() + closed[j]] = std::min(rc[j], 0.0) / step.scales.force;
  }
}

}  // namespace cb
