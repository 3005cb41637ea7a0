// The start of a fixture's step (fixtures.h): from its base, no increment, the load increment
// its constraint asks for and the base's reactions, of the given kind; shared by the tests that
// solve a fixture's step directly.
#pragma once

#include "fixtures.h"

namespace cb::fixtures {

inline StartPoint StartFor(const Fixture& f, StartKind kind) {
  StartPoint start;
  start.kind = kind;
  start.du = Vec::Zero(f.problem.model->num_dofs());
  start.dlambda = f.constraint.target - f.base.lambda;
  start.r = f.base.r;
  return start;
}

}  // namespace cb::fixtures
