// The displacement split of the distributed step system for PETSc's PCFIELDSPLIT: split "0"
// the du rows (the stiffness block of (29), symmetric positive definite once the supports are
// removed, where algebraic multigrid works), split "1" every other row (g^, r^, dlambda[, rho]:
// the gap, complementarity, step-constraint and (32) rows, a few per pair, without the diagonal
// entries a smoother needs; docs/scale-out.md "Linear solves"). Split 0 carries the body's rigid
// modes as its near-null space, which GAMG builds its coarse spaces from. The iterative solve
// applies the split to an augmented system (SetAugmentedSplit) rather than to the Jacobian.
#pragma once

#include <petscpc.h>

#include "model/body_contact_model.h"
#include "model/elastic_body.h"

namespace cb {

// Gives `pc` (of type PCFIELDSPLIT, not yet set up) the two splits of a system whose first
// body.num_dofs() rows are du, this process owning the rows [first, last). Collective.
PetscErrorCode SetDisplacementSplit(PC pc, const ElasticBody& body, PetscInt first, PetscInt last);

// Makes `pc` (of type PCSHELL, not yet set up) the augmented field split, the iterative solve's
// preconditioner. The plain split's Schur complement S = A11 - A10 K^-1 A01 holds, on the closed
// pairs, the contact compliance B K^-1 B^T (B the gap rows' du part, (30)), a dense operator
// whose spectrum spreads like the mesh's 1/h; `selfp` replaces K^-1 by diag(K)^-1 and misses
// that spread, and K itself is singular where contact alone holds the body. The augmented
// split preconditions instead T J, the system whose du rows have gamma B_p^T times each closed
// pair's gap-fixing combination of (30) and (31) added (an augmented Lagrangian: same solution,
// du block K + gamma B^T B). There the compliance becomes (gamma I + (B K^-1 B^T)^-1)^-1, close
// to the diagonal 1 / (gamma + diag) that selfp gives once gamma outweighs K's diagonal, and the
// du block is regular. The inner split (SetDisplacementSplit) takes the options under the
// prefix "al_" after pc's own; "-augmented_alpha" (gamma over the stiffness, default 10) and
// "-augmented_cutoff" (|b| / |a| below which a pair counts as closed, default 1e-2) under pc's.
// Collective.
PetscErrorCode SetAugmentedSplit(PC pc, const BodyContactModel& model, PetscInt first,
                                 PetscInt last);

}  // namespace cb
