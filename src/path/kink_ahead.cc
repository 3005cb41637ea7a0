#include "path/kink_ahead.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "path/stability.h"
#include "path/step_solve.h"

namespace cb {
namespace {

// Pairs whose switching function s = g/L + r/R, extrapolated linearly along the arc length
// from `before` to `at`, changes sign within `reach` ahead of `at`: (distance, pair), nearest
// first.
std::vector<std::pair<double, int>> Crossings(const ContactModel& model,
                                              const ContactScales& scales, const State& before,
                                              const State& at, double reach, double w) {
  const double chord = HNorm(at.u - before.u, at.lambda - before.lambda, w);
  std::vector<std::pair<double, int>> found;
  if (!(chord > 0.0)) return found;
  const Vec g0 = GapsAt(model, before.u);
  const Vec g1 = GapsAt(model, at.u);
  for (int p = 0; p < model.num_pairs(); ++p) {
    const double s0 = g0[p] / scales.length + before.r[p] / scales.force;
    const double s1 = g1[p] / scales.length + at.r[p] / scales.force;
    const double slope = (s1 - s0) / chord;  // per unit arc length
    if (!(s1 * slope < 0.0)) continue;       // not running to zero
    const double distance = -s1 / slope;
    if (distance <= reach) found.emplace_back(distance, p);
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace

KinkAheadFinder::KinkAheadFinder(const ContactModel& model, const ContactScales& scales,
                                 const KinkLocator& locator, const PathOptions& options)
    : model_(model), scales_(scales), locator_(locator), options_(options) {}

std::optional<KinkAhead> KinkAheadFinder::Find(int step, const State& before, const State& at,
                                               const Increment& heading, double reach) const {
  const double w = options_.lambda_weight;
  const double heading_norm = HNorm(heading.du, heading.dlambda, w);
  if (!(heading_norm > 0.0)) return std::nullopt;
  const std::vector<bool> closed_now = ClosedPairs(scales_, GapsAt(model_, at.u), at.r);
  for (const auto& [distance, pair] : Crossings(model_, scales_, before, at, reach, w)) {
    const double t = distance / heading_norm;
    Vec r0 = at.r;
    r0[pair] = 0.0;  // the kink's
    KinkRecord kink = locator_.SolveFrom(step, pair, at, {heading.du * t, heading.dlambda * t}, r0);
    const Vec du = kink.state.u - at.u;
    const double dl = kink.state.lambda - at.lambda;
    const bool ahead = HInner(du, dl, heading.du, heading.dlambda, w) > 0.0;
    if (!SolvedAndVerified(kink.result, kink.verdict) || !ahead || HNorm(du, dl, w) > reach)
      continue;
    kink.between = true;
    KinkAhead found{std::move(kink), {}};
    if (LeavingDirection(found.kink.state, pair, !closed_now[pair], &found.leave)) return found;
  }
  return std::nullopt;
}

// The tangent of the piece where `pair` is closed (closed_after) or open, the other pairs as at
// the kink: A [du; dr] = [f; 0], signed by the pair's feasibility, unit in ||.||_H.
bool KinkAheadFinder::LeavingDirection(const State& kink, int pair, bool closed_after,
                                       Increment* leave) const {
  std::vector<bool> closed = ClosedPairs(scales_, GapsAt(model_, kink.u), kink.r);
  closed[pair] = closed_after;
  const BorderedStiffness stiffness(model_, scales_, kink, closed);
  Vec du, dr;
  if (!stiffness.Solve(model_.load_pattern(), &du, &dr)) return false;
  double growth = 0.0;  // d(-r) on the closed piece, dg on the open one, per unit load
  if (closed_after) {
    growth = -dr[pair];
  } else {
    SpMat gap_jacobian;
    model_.GapJacobian(kink.u, &gap_jacobian);
    growth = -(gap_jacobian.row(pair) * du).value();
  }
  if (!(std::abs(growth) > 0.0) || !du.allFinite()) return false;
  const double sense = growth > 0.0 ? 1.0 : -1.0;
  const double norm = HNorm(du, 1.0, options_.lambda_weight);
  *leave = {du * (sense / norm), sense / norm};
  return true;
}

}  // namespace cb
