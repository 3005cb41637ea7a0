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

// The mean |diagonal| of the du rows of `reduced`, the supported rows' scale, so that they look
// like the others to the smoother's eigenvalue estimate. Collective.
PetscErrorCode NodeBlocks::SupportedRowScale(::Mat reduced, PetscScalar* scale) const {
  PetscReal diagonal_sum = 0.0;
  for (PetscInt i = first_; i < std::min(last_, d_); ++i) {
    PetscScalar value = 0.0;
    PetscCall(MatGetValue(reduced, i, i, &value));
    diagonal_sum += std::abs(value);
  }
  PetscReal sum = 0.0;
  PetscCallMPI(MPI_Allreduce(&diagonal_sum, &sum, 1, MPIU_REAL, MPIU_SUM, comm_));
  *scale = d_ > 0 && sum > 0.0 ? sum / static_cast<PetscReal>(d_) : 1.0;
  return 0;
}

// Preallocates *blocked for `reduced`'s pattern, its storage replaced (PETSc frees the previous
// one), so that the blocked copy is never held twice. A blocked row this process owns whose
// reduced row another process owns (a node whose dofs straddle the ownership boundary) gets the
// widest local row's counts.
PetscErrorCode NodeBlocks::Preallocate(::Mat reduced, ::Mat blocked) const {
  PetscInt own_first = 0, own_last = 0;
  PetscCall(VecGetOwnershipRange(blocked_template_, &own_first, &own_last));
  const auto local = static_cast<std::size_t>(own_last - own_first);
  std::vector<PetscInt> diagonal(local, -1), off(local, 0);
  PetscInt widest = 1;
  for (PetscInt i = first_; i < last_; ++i) {
    PetscInt count = 0, in_block = 0;
    const PetscInt* c = nullptr;
    PetscCall(MatGetRow(reduced, i, &count, &c, nullptr));
    for (PetscInt k = 0; k < count; ++k) {
      const PetscInt column = Blocked(c[k]);
      in_block += column >= own_first && column < own_last ? 1 : 0;
    }
    widest = std::max(widest, count);
    const PetscInt row = Blocked(i);
    if (row >= own_first && row < own_last) {
      diagonal[static_cast<std::size_t>(row - own_first)] = in_block;
      off[static_cast<std::size_t>(row - own_first)] = count - in_block;
    }
    PetscCall(MatRestoreRow(reduced, i, &count, &c, nullptr));  // which zeroes count
  }
  for (std::size_t r = 0; r < local; ++r) {
    if (diagonal[r] >= 0) continue;
    diagonal[r] = std::min<PetscInt>(widest, own_last - own_first);  // supported or straddling
    off[r] = widest;
  }
  PetscCall(MatXAIJSetPreallocation(blocked, 1, diagonal.data(), off.data(), nullptr, nullptr));
  PetscCall(MatSetOption(blocked, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  return 0;
}

PetscErrorCode NodeBlocks::Expand(::Mat reduced, ::Mat* blocked) const {
  PetscScalar scale = 1.0;
  PetscCall(SupportedRowScale(reduced, &scale));
  if (*blocked == nullptr) {
    PetscInt local = 0, global = 0;
    PetscCall(VecGetLocalSize(blocked_template_, &local));
    PetscCall(VecGetSize(blocked_template_, &global));
    PetscCall(MatCreate(comm_, blocked));
    PetscCall(MatSetSizes(*blocked, local, local, global, global));
    PetscCall(MatSetType(*blocked, MATAIJ));
  }
  PetscCall(Preallocate(reduced, *blocked));
  std::vector<PetscInt> columns;
  for (PetscInt i = first_; i < last_; ++i) {
    PetscInt count = 0;
    const PetscInt* c = nullptr;
    const PetscScalar* v = nullptr;
    PetscCall(MatGetRow(reduced, i, &count, &c, &v));
    columns.resize(static_cast<std::size_t>(count));
    for (PetscInt k = 0; k < count; ++k) columns[static_cast<std::size_t>(k)] = Blocked(c[k]);
    const PetscInt row = Blocked(i);
    PetscCall(MatSetValues(*blocked, 1, &row, count, columns.data(), v, INSERT_VALUES));
    PetscCall(MatRestoreRow(reduced, i, &count, &c, &v));
  }
  const int dim = body_.dim();
  for (PetscInt node = node_first_; node < node_last_; ++node) {
    for (int c = 0; c < dim; ++c) {
      if (body_.dofs().dof(static_cast<int>(node), c) >= 0) continue;
      const PetscInt row = dim * node + c;
      PetscCall(MatSetValues(*blocked, 1, &row, 1, &row, &scale, INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(*blocked, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*blocked, MAT_FINAL_ASSEMBLY));
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
