#include "path/turn_back.h"

#include <algorithm>
#include <cmath>

namespace cb {
namespace {

// H-distance from the point (du, dl) to the segment from a to b (increments from x_k).
double DistanceToSegment(const Vec& du, double dl, const Increment& a, const Increment& b,
                         double w) {
  const Vec ab_u = b.du - a.du;
  const double ab_l = b.dlambda - a.dlambda;
  const double ab = HInner(ab_u, ab_l, ab_u, ab_l, w);
  const Vec ap_u = du - a.du;
  const double ap_l = dl - a.dlambda;
  // Parameter s of the closest point a + s (b - a), s in [0, 1].
  const double s = ab > 0.0 ? std::clamp(HInner(ap_u, ap_l, ab_u, ab_l, w) / ab, 0.0, 1.0) : 0.0;
  return HNorm(ap_u - s * ab_u, ap_l - s * ab_l, w);
}

}  // namespace

bool TurnsBack(const StepPoint& answer, const Increment& heading,
               const std::vector<Increment>& trail, double theta, double w) {
  if (HInner(answer.du, answer.dlambda, heading.du, heading.dlambda, w) > 0.0) return false;
  if (trail.empty()) return true;
  Increment from{Vec::Zero(answer.du.size()), 0.0};  // x_k
  for (const Increment& to : trail) {
    if (DistanceToSegment(answer.du, answer.dlambda, from, to, w) <= 0.05 * theta) return true;
    from = to;
  }
  return false;
}

}  // namespace cb
