// What of each obstacle a figure or ParaView shows: its zero level set near the body
// (obstacle_geometry.h), except for a half-space that serves one contact pair alone (the
// per-pair planes of hertz-3d's paraboloid gap, one tangent plane per node), which is drawn as
// a patch around that pair's node, its half-width half the node's shortest element edge to
// another paired node (the node spacing on the contact face): the
// patches of all pairs tile the obstacle's surface under the contact face instead of stacking
// one plate the size of the body per pair.
#pragma once

#include <vector>

#include "harness/obstacle_geometry.h"
#include "model/body_contact_model.h"

namespace cb::harness {

// The drawn surface of each obstacle of `model`, in the order of model.obstacles().
std::vector<SurfaceGeometry> DrawnObstacles(const BodyContactModel& model);

}  // namespace cb::harness
