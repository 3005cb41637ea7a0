// The displacement split of the distributed step system for PETSc's PCFIELDSPLIT: split "0"
// the du rows (the stiffness block of (29), symmetric positive definite once the supports are
// removed, where algebraic multigrid works), split "1" every other row (g^, r^, dlambda[, rho]:
// the gap, complementarity, step-constraint and (32) rows, a few per pair, without the diagonal
// entries a smoother needs; docs/scale-out.md "Linear solves"). Split 0 carries the body's rigid
// modes as its near-null space, which GAMG builds its coarse spaces from.
#pragma once

#include <petscpc.h>

#include "model/elastic_body.h"

namespace cb {

// Gives `pc` (of type PCFIELDSPLIT, not yet set up) the two splits of a system whose first
// body.num_dofs() rows are du, this process owning the rows [first, last). Collective.
PetscErrorCode SetDisplacementSplit(PC pc, const ElasticBody& body, PetscInt first, PetscInt last);

}  // namespace cb
