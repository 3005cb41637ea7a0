#include "path/turn_back.h"

#include <algorithm>
#include <cmath>

namespace cb {
namespace {

// H-distance from the point x_k + (du, dl) to the segment from x_{k-1} = x_k - (pu, pl) to x_k.
double DistanceToPreviousSegment(const Vec& du, double dl, const Vec& pu, double pl, double w) {
  const double pp = HInner(pu, pl, pu, pl, w);
  // Parameter s of the closest point x_k - s (pu, pl), s in [0, 1].
  const double s = pp > 0.0 ? std::clamp(-HInner(du, dl, pu, pl, w) / pp, 0.0, 1.0) : 0.0;
  const Vec eu = du + s * pu;
  const double el = dl + s * pl;
  return HNorm(eu, el, w);
}

}  // namespace

bool TurnsBack(const StepPoint& answer, const Increment& previous, bool have_segment, double theta,
               double w) {
  if (HInner(answer.du, answer.dlambda, previous.du, previous.dlambda, w) > 0.0) return false;
  if (!have_segment) return true;
  return DistanceToPreviousSegment(answer.du, answer.dlambda, previous.du, previous.dlambda, w) <=
         0.05 * theta;
}

}  // namespace cb
