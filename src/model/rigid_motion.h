// Whether supports and contact pairs restrain a body's rigid-body motions: the translations and
// rotations of its reference configuration (2-D: 2 + 1, 3-D: 3 + 3; fewer for a degenerate
// body, e.g. nodes on one line in 3-D, which no rotation about that line moves). A motion that
// neither restrains leaves the step equations (29) singular. The test is one of rank: the
// constraint rows (each supported component; each pair's obstacle normal at its node) applied
// to the rigid-body modes. Contact is unilateral, so passing the test is necessary, not
// sufficient, for the pairs to hold the body.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model/body_contact_model.h"
#include "model/elastic_body.h"
#include "model/obstacle.h"

namespace cb {

struct RigidMotionRestraint {
  int modes = 0;        // independent rigid-body motions of the body
  int constraints = 0;  // constraint rows: supported components and pairs with a normal
  int restrained = 0;   // independent motions the constraints restrain (at most `modes`)
  // One motion left free, e.g. "rotation about z" (a rotation when a free motion has one,
  // else the dominant translation); empty when none is.
  std::string free_example;

  int free() const { return modes - restrained; }
};

// The restraint of `body`'s rigid-body motions by its supports (its DofMap) and `pairs` against
// `obstacles`. Throws std::invalid_argument for a pair naming an unknown node or obstacle.
RigidMotionRestraint CheckRigidMotionRestraint(
    const ElasticBody& body, const std::vector<std::shared_ptr<const Obstacle>>& obstacles,
    const std::vector<ContactPair>& pairs);

}  // namespace cb
