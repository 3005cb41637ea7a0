// What lies ahead of the path at a contact change (docs/method.md section 10): the pairs whose
// switching function s = g/L + r/R runs to zero along the path, and the tangent of the piece the
// path goes on along once a pair has changed status. Shared by the step onto a kink ahead
// (kink_ahead.h) and the corner prediction (corner_prediction.h).
#pragma once

#include <utility>
#include <vector>

#include "path/arc_length_norm.h"
#include "path/path.h"

namespace cb {

// Pairs whose switching function, extrapolated linearly along the arc length from `before` to
// `at`, changes sign within `reach` ahead of `at`: (distance, pair), nearest first.
std::vector<std::pair<double, int>> SwitchingCrossings(const ContactModel& model,
                                                       const ContactScales& scales,
                                                       const State& before, const State& at,
                                                       double reach, double lambda_weight);

// The tangent at `state` of the piece where `pair` is closed (closed_after) or open, the other
// pairs as at `state`: A [du; dr] = [f; 0], signed so that the pair stays feasible (a closed
// pair's reaction grows in compression, an open pair's gap opens), unit in ||.||_H. False when
// the bordered stiffness is singular or the pair's status does not move along it.
bool PieceTangent(const ContactModel& model, const ContactScales& scales, const State& state,
                  int pair, bool closed_after, double lambda_weight, Increment* tangent);

}  // namespace cb
