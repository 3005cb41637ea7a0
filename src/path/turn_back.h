// The guard against an arc-length step turning back on the path: (33) has two roots, and the
// one wanted goes on along the path, not back onto the part already traced.
#pragma once

#include <vector>

#include "path/arc_length_norm.h"
#include "step/step_problem.h"

namespace cb {

// Whether `answer` (an increment from the last accepted state x_k) turns back. `heading` is the
// direction the path goes on in at x_k (the increment that reached it, or from a kink within
// it; the tangent on the first step). `trail` holds the points of the path already traced
// behind x_k, as increments from x_k, nearest first: x_k - heading (x_{k-1}, or the kink), then
// the accepted states before it, covering at least twice the nominal theta of path; empty on
// the first step.
//
// The other root of (33) lies on the path just traced (exactly at x_{k-1} when theta is
// unchanged), so an answer is rejected when it points backwards AND lies within 5% of theta of
// the polyline through x_k and the trail. The inner product alone is not enough: at a kink the
// path may turn by more than 90 degrees, and the correct root then also points backwards, but
// away from the path traced. The trail reaches beyond x_{k-1} because theta doubles back after
// cut-backs: a step of theta from x_k whose previous step was theta / 2 has its other root
// behind x_{k-1} (measured on two-bar-obstacle with axial_stiffness = 1: the step after a
// cut-back near the floor returned to the rising side of the limit point, unguarded).
// Without a trail the answer must not point against the tangent.
bool TurnsBack(const StepPoint& answer, const Increment& heading,
               const std::vector<Increment>& trail, double theta, double w);

}  // namespace cb
