// The step system with every node's components, for algebraic multigrid that knows elasticity.
// The step system's du rows are the free dofs only (DofMap numbers the free components node by
// node and skips the supported ones), so a body with supports has nodes of 1, 2 or 3 rows and
// PETSc's GAMG, which aggregates whole nodes only under a constant block size, would aggregate
// single components and lose the rigid-body modes. The node-blocked system has dim rows per
// node, in node order, then the step system's other rows: the rows of the free dofs are the step
// system's (columns mapped the same way), a supported component's row is kept as an identity row
// scaled by the mean stiffness diagonal (decoupled, so the solution on the free rows is
// unchanged: with M = [A 0; 0 s I], M^-1 (Q r) = Q A^-1 r for the injection Q). Each process owns
// the nodes whose first free dof (or, for a fully supported node, the next free dof after it) it
// owns, so that its blocked rows are whole nodes.
#pragma once

#include <petscmat.h>

#include <vector>

#include "model/elastic_body.h"

namespace cb {

class NodeBlocks {
 public:
  // For a system of `size` rows whose first body.num_dofs() are du, this process owning the
  // rows [first, last). Collective.
  NodeBlocks(MPI_Comm comm, const ElasticBody& body, PetscInt size, PetscInt first, PetscInt last);
  ~NodeBlocks();
  NodeBlocks(const NodeBlocks&) = delete;
  NodeBlocks& operator=(const NodeBlocks&) = delete;

  // The node-blocked matrix of `reduced` (that system's layout) into *blocked: created when
  // null, else its storage replaced and refilled (one copy at a time, whatever the pattern).
  // Collective.
  PetscErrorCode Expand(::Mat reduced, ::Mat* blocked) const;
  // A vector of the step system into the node-blocked layout (0 on the supported rows), and back.
  PetscErrorCode ToBlocked(::Vec reduced, ::Vec blocked) const;
  PetscErrorCode ToReduced(::Vec blocked, ::Vec reduced) const;
  // A vector of the node-blocked layout.
  PetscErrorCode CreateBlockedVec(::Vec* v) const;

  // The node rows this process owns in the node-blocked layout, [node_first, node_last) times
  // dim, and its other rows [rest_first, rest_last).
  PetscInt node_first() const { return node_first_; }
  PetscInt node_last() const { return node_last_; }
  PetscInt rest_first() const { return rest_first_; }
  PetscInt rest_last() const { return rest_last_; }
  // The blocked index of the step system's row i.
  PetscInt Blocked(PetscInt i) const;

  // The body's rigid-body modes (3 in 2-D, 6 in 3-D) from the reference coordinates of this
  // process's nodes, on the node rows of the blocked layout (MatNullSpaceCreateRigidBody).
  // Collective.
  PetscErrorCode RigidModes(MatNullSpace* space) const;

 private:
  PetscErrorCode SupportedRowScale(::Mat reduced, PetscScalar* scale) const;
  PetscErrorCode Preallocate(::Mat reduced, ::Mat blocked) const;

  MPI_Comm comm_;
  const ElasticBody& body_;
  PetscInt d_ = 0, size_ = 0, first_ = 0, last_ = 0;
  PetscInt node_first_ = 0, node_last_ = 0, rest_first_ = 0, rest_last_ = 0;
  std::vector<PetscInt> blocked_of_free_;  // dim * node + component of each free dof
  ::Vec reduced_template_ = nullptr, blocked_template_ = nullptr;
  VecScatter scatter_ = nullptr;  // reduced -> blocked
};

}  // namespace cb
