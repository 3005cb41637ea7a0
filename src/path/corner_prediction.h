// The corner prediction (docs/method.md section 10, item 6): a step whose prediction runs
// across a contact change is predicted along the path's two pieces instead of the straight
// line. The straight prediction of a step across a closing pair ends inside the obstacle, and
// Newton on the smoothed equations then creeps (damped steps of 0.1 for up to 40 iterations on
// P3) towards an answer just past the corner, near the degenerate point g_p = r_p = 0.
#pragma once

#include <optional>

#include "path/arc_length_norm.h"
#include "path/path.h"

namespace cb {

// The prediction `prediction` (an increment from `at`, reached from accepted state `before`),
// bent where the first pair's switching function, extrapolated from `before` to `at`, changes
// sign within it: along `prediction` to that point, then along the tangent of the piece with
// the pair's status switched (contact_change_ahead.h) for the rest of its length. nullopt when
// no pair changes within it or the piece's tangent cannot be formed.
std::optional<Increment> CornerPrediction(const ContactModel& model, const ContactScales& scales,
                                          const State& before, const State& at,
                                          const Increment& prediction, double lambda_weight);

}  // namespace cb
