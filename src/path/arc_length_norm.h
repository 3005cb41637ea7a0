// The norm the arc-length constraint (33) measures steps in: ||(du, dlambda)||_H =
// sqrt(du . du + w^2 dlambda^2), w the weight of the load parameter.
#pragma once

#include <cmath>

#include "core/types.h"

namespace cb {

// An increment (du, dlambda) of the path: a step taken, or a direction to take one in.
struct Increment {
  Vec du;
  double dlambda = 0.0;
};

// <(a, la), (b, lb)>_H.
inline double HInner(const Vec& a, double la, const Vec& b, double lb, double w) {
  return a.dot(b) + w * w * la * lb;
}

inline double HNorm(const Vec& du, double dlambda, double w) {
  return std::sqrt(HInner(du, dlambda, du, dlambda, w));
}

}  // namespace cb
