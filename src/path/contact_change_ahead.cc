#include "path/contact_change_ahead.h"

#include <algorithm>
#include <cmath>

#include "path/stability.h"

namespace cb {

std::vector<std::pair<double, int>> SwitchingCrossings(const ContactModel& model,
                                                       const ContactScales& scales,
                                                       const State& before, const State& at,
                                                       double reach, double lambda_weight) {
  const double chord = HNorm(at.u - before.u, at.lambda - before.lambda, lambda_weight);
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

bool PieceTangent(const ContactModel& model, const ContactScales& scales, const State& state,
                  int pair, bool closed_after, double lambda_weight, Increment* tangent) {
  std::vector<bool> closed = ClosedPairs(scales, GapsAt(model, state.u), state.r);
  closed[pair] = closed_after;
  const BorderedStiffness stiffness(model, scales, state, closed);
  Vec du, dr;
  if (!stiffness.Solve(model.load_pattern(), &du, &dr)) return false;
  double growth = 0.0;  // d(-r) on the closed piece, dg on the open one, per unit load
  if (closed_after) {
    growth = -dr[pair];
  } else {
    SpMat gap_jacobian;
    model.GapJacobian(state.u, &gap_jacobian);
    growth = -(gap_jacobian.row(pair) * du).value();
  }
  if (!(std::abs(growth) > 0.0) || !du.allFinite()) return false;
  const double sense = growth > 0.0 ? 1.0 : -1.0;
  const double norm = HNorm(du, 1.0, lambda_weight);
  *tangent = {du * (sense / norm), sense / norm};
  return true;
}

}  // namespace cb
