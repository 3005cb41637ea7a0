// The checks of a body problem that need the whole body: every node connected, the rigid-body
// modes held, and every contact pair starting outside its obstacle. Internal to the
// problem-file reader.
#pragma once

#include <memory>
#include <vector>

#include "io/problem_file_body.h"
#include "io/problem_file_obstacles.h"
#include "model/body_contact_model.h"

namespace cb::io::reading {

// A node on no member or element has no stiffness: the system would be singular. `uses`: how
// many members or elements (`what`) each node belongs to.
void CheckConnected(const BodyInput& in, const std::vector<int>& uses, const char* what);

// Rigid-body modes must be restrained: by the supports alone when there are no contact pairs,
// or by supports and contact normals together (model/rigid_motion.h).
void CheckHeld(const BodyInput& in, const ElasticBody& body,
               const std::vector<std::shared_ptr<const Obstacle>>& obstacles,
               const std::vector<ContactPair>& pairs);

// Pairs start with a non-negative gap; a node inside its obstacle usually means a normal that
// points the wrong way (it points INTO the obstacle).
void CheckInitialGaps(const BodyInput& in, const BodyContactModel& model,
                      const Obstacles& obstacles);

}  // namespace cb::io::reading
