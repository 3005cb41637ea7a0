// The guard against an arc-length step turning back on the path: (33) has two roots, and the
// one wanted goes on along the path, not back onto the part already traced.
#pragma once

#include "path/arc_length_norm.h"
#include "step/step_problem.h"

namespace cb {

// Whether `answer` (an increment from the last accepted state x_k) turns back. `previous` is
// the increment that reached x_k (have_segment: the segment from x_{k-1} = x_k - previous to
// x_k was traced) or, on the first step, the tangent (no segment).
//
// The other root of (33) lies on the segment just traced (exactly at x_{k-1} when theta is
// unchanged), so an answer is rejected when it points backwards AND lies within 5% of theta of
// that segment. The inner product alone is not enough: at a kink the path may turn by more
// than 90 degrees, and the correct root then also points backwards, but away from the segment.
// Without a segment the answer must not point against the tangent.
bool TurnsBack(const StepPoint& answer, const Increment& previous, bool have_segment, double theta,
               double w);

}  // namespace cb
