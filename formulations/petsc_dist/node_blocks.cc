#include "formulations/petsc_dist/node_blocks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cb {

namespace {

void Check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc failed in ") + what);
}

// The number of free dofs on the nodes before each node (DofMap numbers them node by node), for
// nodes 0..num_nodes.
std::vector<PetscInt> FreeDofsBefore(const DofMap& dofs) {
  std::vector<PetscInt> before(static_cast<std::size_t>(dofs.num_nodes()) + 1, 0);
  for (int node = 0; node < dofs.num_nodes(); ++node) {
    PetscInt free = 0;
    for (int c = 0; c < dofs.dim(); ++c) free += dofs.dof(node, c) >= 0 ? 1 : 0;
    before[static_cast<std::size_t>(node) + 1] = before[static_cast<std::size_t>(node)] + free;
  }
  return before;
}

}  // namespace

NodeBlocks::NodeBlocks(MPI_Comm comm, const ElasticBody& body, PetscInt size, PetscInt first,
                       PetscInt last)
    : comm_(comm), body_(body), d_(body.num_dofs()), size_(size), first_(first), last_(last) {
  const DofMap& dofs = body.dofs();
  const int dim = dofs.dim(), num_nodes = dofs.num_nodes();
  const std::vector<PetscInt> before = FreeDofsBefore(dofs);
  // The node's owner owns its first free dof, or the next one after it (the last one at the end).
  const auto owner_row = [&](int node) {
    return std::min(before[static_cast<std::size_t>(node)], d_ - 1);
  };
  const PetscInt du_first = std::min(first, d_), du_last = std::min(last, d_);
  node_first_ = node_last_ = 0;
  while (node_first_ < num_nodes && owner_row(static_cast<int>(node_first_)) < du_first) {
    ++node_first_;
  }
  node_last_ = node_first_;
  while (node_last_ < num_nodes && owner_row(static_cast<int>(node_last_)) < du_last) ++node_last_;
  rest_first_ = std::max(first, d_);
  rest_last_ = std::max(last, d_);

  blocked_of_free_.assign(static_cast<std::size_t>(d_), 0);
  for (int node = 0; node < num_nodes; ++node) {
    for (int c = 0; c < dim; ++c) {
      const int k = dofs.dof(node, c);
      if (k >= 0) blocked_of_free_[static_cast<std::size_t>(k)] = dim * node + c;
    }
  }

  Check(VecCreateMPI(comm, last - first, size, &reduced_template_), "VecCreateMPI");
  Check(CreateBlockedVec(&blocked_template_), "VecCreateMPI");
  std::vector<PetscInt> to;
  for (PetscInt i = first; i < last; ++i) to.push_back(Blocked(i));
  IS from_is = nullptr, to_is = nullptr;
  Check(ISCreateStride(comm, last - first, first, 1, &from_is), "ISCreateStride");
  Check(
      ISCreateGeneral(comm, static_cast<PetscInt>(to.size()), to.data(), PETSC_COPY_VALUES, &to_is),
      "ISCreateGeneral");
  Check(VecScatterCreate(reduced_template_, from_is, blocked_template_, to_is, &scatter_),
        "VecScatterCreate");
  Check(ISDestroy(&from_is), "ISDestroy");
  Check(ISDestroy(&to_is), "ISDestroy");
}

NodeBlocks::~NodeBlocks() {
  VecScatterDestroy(&scatter_);
  VecDestroy(&reduced_template_);
  VecDestroy(&blocked_template_);
}

PetscInt NodeBlocks::Blocked(PetscInt i) const {
  if (i < d_) return blocked_of_free_[static_cast<std::size_t>(i)];
  return body_.dim() * static_cast<PetscInt>(body_.num_nodes()) + (i - d_);
}

PetscErrorCode NodeBlocks::CreateBlockedVec(::Vec* v) const {
  const PetscInt dim = body_.dim();
  PetscCall(VecCreateMPI(comm_, dim * (node_last_ - node_first_) + (rest_last_ - rest_first_),
                         dim * body_.num_nodes() + (size_ - d_), v));
  return 0;
}

PetscErrorCode NodeBlocks::Expand(::Mat reduced, ::Mat* blocked) const {
  std::vector<PetscInt> rows, cols;
  std::vector<PetscScalar> values;
  PetscReal diagonal_sum = 0.0;
  for (PetscInt i = first_; i < last_; ++i) {
    PetscInt count = 0;
    const PetscInt* c = nullptr;
    const PetscScalar* v = nullptr;
    PetscCall(MatGetRow(reduced, i, &count, &c, &v));
    for (PetscInt k = 0; k < count; ++k) {
      rows.push_back(Blocked(i));
      cols.push_back(Blocked(c[k]));
      values.push_back(v[k]);
      if (i < d_ && c[k] == i) diagonal_sum += std::abs(v[k]);
    }
    PetscCall(MatRestoreRow(reduced, i, &count, &c, &v));
  }
  // The supported rows' scale: the mean stiffness diagonal, so that they look like the others
  // to the smoother's eigenvalue estimate.
  PetscReal sum = 0.0;
  PetscCallMPI(MPI_Allreduce(&diagonal_sum, &sum, 1, MPIU_REAL, MPIU_SUM, comm_));
  const PetscScalar scale = d_ > 0 && sum > 0.0 ? sum / static_cast<PetscReal>(d_) : 1.0;
  const int dim = body_.dim();
  for (PetscInt node = node_first_; node < node_last_; ++node) {
    for (int c = 0; c < dim; ++c) {
      if (body_.dofs().dof(static_cast<int>(node), c) >= 0) continue;
      rows.push_back(dim * node + c);
      cols.push_back(dim * node + c);
      values.push_back(scale);
    }
  }
  PetscCall(MatDestroy(blocked));
  PetscInt local = 0, global = 0;
  PetscCall(VecGetLocalSize(blocked_template_, &local));
  PetscCall(VecGetSize(blocked_template_, &global));
  PetscCall(MatCreate(comm_, blocked));
  PetscCall(MatSetSizes(*blocked, local, local, global, global));
  PetscCall(MatSetType(*blocked, MATAIJ));
  PetscCall(MatSetPreallocationCOO(*blocked, static_cast<PetscCount>(rows.size()), rows.data(),
                                   cols.data()));
  PetscCall(MatSetValuesCOO(*blocked, values.data(), INSERT_VALUES));
  return 0;
}

PetscErrorCode NodeBlocks::ToBlocked(::Vec reduced, ::Vec blocked) const {
  PetscCall(VecSet(blocked, 0.0));
  PetscCall(VecScatterBegin(scatter_, reduced, blocked, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter_, reduced, blocked, INSERT_VALUES, SCATTER_FORWARD));
  return 0;
}

PetscErrorCode NodeBlocks::ToReduced(::Vec blocked, ::Vec reduced) const {
  PetscCall(VecScatterBegin(scatter_, blocked, reduced, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(scatter_, blocked, reduced, INSERT_VALUES, SCATTER_REVERSE));
  return 0;
}

PetscErrorCode NodeBlocks::RigidModes(MatNullSpace* space) const {
  const int dim = body_.dim();
  ::Vec coordinates = nullptr;
  PetscCall(VecCreate(comm_, &coordinates));
  PetscCall(VecSetSizes(coordinates, dim * (node_last_ - node_first_), dim * body_.num_nodes()));
  PetscCall(VecSetBlockSize(coordinates, dim));
  PetscCall(VecSetType(coordinates, VECMPI));
  PetscScalar* a = nullptr;
  PetscCall(VecGetArrayWrite(coordinates, &a));
  for (PetscInt node = node_first_; node < node_last_; ++node) {
    const Point x = body_.reference(static_cast<int>(node));
    for (int c = 0; c < dim; ++c) a[dim * (node - node_first_) + c] = x[c];
  }
  PetscCall(VecRestoreArrayWrite(coordinates, &a));
  PetscCall(MatNullSpaceCreateRigidBody(coordinates, space));
  PetscCall(VecDestroy(&coordinates));
  return 0;
}

}  // namespace cb
