#include "formulations/petsc_dist/field_split.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "formulations/petsc_dist/node_blocks.h"

namespace cb {

namespace {

int NumRigidModes(int dim) { return dim == 3 ? 6 : dim == 2 ? 3 : 1; }

// Component c of rigid mode `mode` at `x` (relative to the centroid): the translations, then
// the rotations (about the normal in 2-D, about each axis in 3-D).
double RigidMode(int mode, const Point& x, int c) {
  const int dim = static_cast<int>(x.size());
  if (mode < dim) return mode == c ? 1.0 : 0.0;
  if (dim == 2) return c == 0 ? -x[1] : x[0];
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(mode - dim);
  return axis.cross(Eigen::Vector3d(x[0], x[1], x[2]))[c];
}

Point Centroid(const ElasticBody& body) {
  Point sum = Point::Zero(body.dim());
  for (int node = 0; node < body.num_nodes(); ++node) sum += body.reference(node);
  return sum / std::max(1, body.num_nodes());
}

// The rigid modes on this process's du rows [du_first, du_last), orthonormalised (modes the
// supports leave no trace of are dropped), as a near-null space.
PetscErrorCode MakeRigidModes(MPI_Comm comm, const ElasticBody& body, PetscInt du_first,
                              PetscInt du_last, MatNullSpace* space) {
  const Point centroid = Centroid(body);
  std::vector<::Vec> modes;
  for (int mode = 0; mode < NumRigidModes(body.dim()); ++mode) {
    ::Vec v = nullptr;
    PetscCall(VecCreateMPI(comm, du_last - du_first, body.num_dofs(), &v));
    PetscScalar* a = nullptr;
    PetscCall(VecGetArrayWrite(v, &a));
    std::fill_n(a, du_last - du_first, 0.0);
    for (int node = 0; node < body.num_nodes(); ++node) {
      const Point x = body.reference(node) - centroid;
      for (int c = 0; c < body.dim(); ++c) {
        const int k = body.dofs().dof(node, c);
        if (k >= du_first && k < du_last) a[k - du_first] = RigidMode(mode, x, c);
      }
    }
    PetscCall(VecRestoreArrayWrite(v, &a));
    for (::Vec kept : modes) {
      PetscScalar dot = 0.0;
      PetscCall(VecDot(v, kept, &dot));
      PetscCall(VecAXPY(v, -dot, kept));
    }
    PetscReal norm = 0.0;
    PetscCall(VecNormalize(v, &norm));
    if (norm > 1e-8) {
      modes.push_back(v);
    } else {
      PetscCall(VecDestroy(&v));
    }
  }
  PetscCall(MatNullSpaceCreate(comm, PETSC_FALSE, static_cast<PetscInt>(modes.size()), modes.data(),
                               space));
  for (::Vec& v : modes) PetscCall(VecDestroy(&v));
  return 0;
}

// dim when every node has all its components free, numbered node by node, and this process's
// rows hold whole nodes (GAMG then aggregates nodes, not single components); otherwise 1.
PetscInt NodeBlockSize(const ElasticBody& body, PetscInt du_first, PetscInt du_last) {
  const int dim = body.dim();
  if (du_first % dim != 0 || du_last % dim != 0) return 1;
  for (int node = 0; node < body.num_nodes(); ++node) {
    for (int c = 0; c < dim; ++c) {
      if (body.dofs().dof(node, c) != dim * node + c) return 1;
    }
  }
  return dim;
}

// Splits "0" (du, carrying the near-null space `rigid` for GAMG) and "1" (the rest) of `pc`.
PetscErrorCode SetSplits(PC pc, IS du, IS rest, MatNullSpace rigid) {
  // PCFIELDSPLIT hands a split's "nearnullspace" to the split's matrix (for GAMG).
  PetscCall(PetscObjectCompose(reinterpret_cast<PetscObject>(du), "nearnullspace",
                               reinterpret_cast<PetscObject>(rigid)));
  PetscCall(PCFieldSplitSetIS(pc, "0", du));
  PetscCall(PCFieldSplitSetIS(pc, "1", rest));
  return 0;
}

// The splits of the node-blocked system (node_blocks.h): whole nodes, block size dim, the rigid
// modes from the coordinates.
PetscErrorCode SetBlockedSplit(PC pc, const NodeBlocks& blocks, int dim) {
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(pc));
  IS du = nullptr, rest = nullptr;
  PetscCall(ISCreateStride(comm, dim * (blocks.node_last() - blocks.node_first()),
                           dim * blocks.node_first(), 1, &du));
  PetscCall(ISSetBlockSize(du, dim));
  PetscCall(ISCreateStride(comm, blocks.rest_last() - blocks.rest_first(),
                           blocks.Blocked(blocks.rest_first()), 1, &rest));
  MatNullSpace rigid = nullptr;
  PetscCall(blocks.RigidModes(&rigid));
  PetscCall(SetSplits(pc, du, rest, rigid));
  PetscCall(MatNullSpaceDestroy(&rigid));
  PetscCall(ISDestroy(&du));
  PetscCall(ISDestroy(&rest));
  return 0;
}

}  // namespace

PetscErrorCode SetDisplacementSplit(PC pc, const ElasticBody& body, PetscInt first, PetscInt last) {
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(pc));
  const PetscInt d = body.num_dofs();
  const PetscInt du_first = std::min(first, d), du_last = std::min(last, d);
  const PetscInt rest_first = std::max(first, d);
  IS du = nullptr, rest = nullptr;
  PetscCall(ISCreateStride(comm, du_last - du_first, du_first, 1, &du));
  PetscCall(ISSetBlockSize(du, NodeBlockSize(body, du_first, du_last)));
  PetscCall(ISCreateStride(comm, std::max<PetscInt>(0, last - rest_first), rest_first, 1, &rest));
  MatNullSpace rigid = nullptr;
  PetscCall(MakeRigidModes(comm, body, du_first, du_last, &rigid));
  PetscCall(SetSplits(pc, du, rest, rigid));
  PetscCall(MatNullSpaceDestroy(&rigid));
  PetscCall(ISDestroy(&du));
  PetscCall(ISDestroy(&rest));
  return 0;
}

namespace {

// The augmented preconditioner's state: T, T J and the field split of T J (its options under
// the prefix "al_"), rebuilt at every set-up (the closed pairs change with the iterate).
struct Augmented {
  PetscInt d = 0, nc = 0;
  PetscReal alpha = 10.0, cutoff = 1e-2;
  PC inner = nullptr;
  ::Mat t = nullptr, tj = nullptr;
  ::Vec weights = nullptr, scaled = nullptr, work = nullptr;
  // The inner split solves the node-blocked T J (node_blocks.h), so that GAMG gets whole nodes
  // and the rigid modes whatever the supports.
  std::unique_ptr<NodeBlocks> blocks;
  ::Mat blocked_tj = nullptr;
  ::Vec blocked_in = nullptr, blocked_out = nullptr;
};

// Calls visit(column, value) on each entry of row `row` (owned here) of `j`.
template <class Visit>
PetscErrorCode VisitRow(::Mat j, PetscInt row, Visit visit) {
  PetscInt count = 0;
  const PetscInt* cols = nullptr;
  const PetscScalar* vals = nullptr;
  PetscCall(MatGetRow(j, row, &count, &cols, &vals));
  for (PetscInt k = 0; k < count; ++k) visit(cols[k], vals[k]);
  PetscCall(MatRestoreRow(j, row, &count, &cols, &vals));
  return 0;
}

PetscErrorCode DestroyAugmented(PC pc) {
  Augmented* a = nullptr;
  PetscCall(PCShellGetContext(pc, &a));
  if (a == nullptr) return 0;
  PetscCall(MatDestroy(&a->t));
  PetscCall(MatDestroy(&a->tj));
  PetscCall(VecDestroy(&a->weights));
  PetscCall(VecDestroy(&a->scaled));
  PetscCall(VecDestroy(&a->work));
  PetscCall(MatDestroy(&a->blocked_tj));
  PetscCall(VecDestroy(&a->blocked_in));
  PetscCall(VecDestroy(&a->blocked_out));
  PetscCall(PCDestroy(&a->inner));
  delete a;
  PetscCall(PCShellSetContext(pc, nullptr));
  return 0;
}

// Pair p's complementarity row (31) has a = dF3_p / dg^_p and b = dF3_p / dr^_p; with row (30)_p
// (dg^_p + B_p du) it combines to a row(30)_p - row(31)_p = a B_p du - b dr^_p, free of g^_p.
// The pair counts as closed where |b| <= cutoff |a| (the active set's closed pairs have b = 0;
// Fischer-Burmeister's rows approach it as g^_p -> 0 < r^_p), and gets w_p = a / (a^2 + b^2)
// at index d + p of `weights` and a w_p of `scaled` (both 0 elsewhere).
PetscErrorCode PairWeights(::Mat j, const Augmented& a, ::Vec weights, ::Vec scaled) {
  PetscInt row_first = 0, row_last = 0;
  PetscCall(MatGetOwnershipRange(j, &row_first, &row_last));
  PetscCall(VecSet(weights, 0.0));
  PetscCall(VecSet(scaled, 0.0));
  for (PetscInt p = 0; p < a.nc; ++p) {
    const PetscInt row = a.d + a.nc + p;
    if (row < row_first || row >= row_last) continue;
    PetscScalar ga = 0.0, rb = 0.0;
    PetscCall(VisitRow(j, row, [&](PetscInt col, PetscScalar value) {
      if (col == a.d + p) ga = value;
      if (col == a.d + a.nc + p) rb = value;
    }));
    const PetscScalar norm = ga * ga + rb * rb;
    const PetscScalar w = norm > 0.0 && std::abs(rb) <= a.cutoff * std::abs(ga) ? ga / norm : 0.0;
    PetscCall(VecSetValue(weights, a.d + p, w, INSERT_VALUES));
    PetscCall(VecSetValue(scaled, a.d + p, ga * w, INSERT_VALUES));
  }
  for (::Vec v : {weights, scaled}) {
    PetscCall(VecAssemblyBegin(v));
    PetscCall(VecAssemblyEnd(v));
  }
  return 0;
}

// gamma = alpha max_k K_kk / max_p |B_p|^2 (K the du block, B_p the du part of row (30)_p):
// gamma B_p^T B_p then outweighs the stiffness at a closed pair's node by about alpha, which is
// what makes the diagonal approximation of the Schur complement close (field_split.h).
PetscErrorCode Gamma(::Mat j, const Augmented& a, PetscReal* gamma) {
  PetscInt row_first = 0, row_last = 0;
  PetscCall(MatGetOwnershipRange(j, &row_first, &row_last));
  PetscReal stiff = 0.0, gap = 0.0;
  for (PetscInt row = row_first; row < row_last; ++row) {
    const bool du_row = row < a.d, gap_row = row >= a.d && row < a.d + a.nc;
    if (!du_row && !gap_row) continue;
    PetscReal norm = 0.0;
    PetscCall(VisitRow(j, row, [&](PetscInt col, PetscScalar value) {
      if (du_row && col == row) stiff = std::max(stiff, std::abs(value));
      if (gap_row && col < a.d) norm += value * value;
    }));
    gap = std::max(gap, norm);
  }
  PetscReal local[2] = {stiff, gap}, global[2] = {0.0, 0.0};
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPIU_REAL, MPIU_MAX,
                             PetscObjectComm(reinterpret_cast<PetscObject>(j))));
  *gamma = global[1] > 0.0 ? a.alpha * global[0] / global[1] : 0.0;
  return 0;
}

// T = I + gamma sum_p w_p B_p^T (a_p e_(30)_p - e_(31)_p)^T (e_i the i-th unit row): adds to
// the du rows gamma w_p B_p^T times pair p's combination above, so that the du block of T J is
// K + gamma sum_p a_p w_p B_p^T B_p.
PetscErrorCode MakeT(::Mat j, Augmented* a) {
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(j));
  PetscInt row_first = 0, row_last = 0;
  PetscCall(MatGetOwnershipRange(j, &row_first, &row_last));
  if (a->weights == nullptr) {
    PetscCall(MatCreateVecs(j, &a->weights, &a->work));
    PetscCall(VecDuplicate(a->weights, &a->scaled));
  }
  PetscCall(PairWeights(j, *a, a->weights, a->scaled));
  PetscReal gamma = 0.0;
  PetscCall(Gamma(j, *a, &gamma));
  PetscCall(MatDestroy(&a->t));
  PetscCall(MatCreate(comm, &a->t));
  PetscCall(MatSetSizes(a->t, row_last - row_first, row_last - row_first, PETSC_DETERMINE,
                        PETSC_DETERMINE));
  PetscCall(MatSetType(a->t, MATMPIAIJ));  // the Jacobian's type, which MatMatMult needs
  PetscCall(MatMPIAIJSetPreallocation(a->t, 3, nullptr, 2, nullptr));
  PetscCall(MatSetOption(a->t, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt row = row_first; row < row_last; ++row) {
    PetscCall(MatSetValue(a->t, row, row, 1.0, ADD_VALUES));
  }
  const PetscScalar *w = nullptr, *aw = nullptr;
  PetscCall(VecGetArrayRead(a->weights, &w));
  PetscCall(VecGetArrayRead(a->scaled, &aw));
  for (PetscInt p = 0; p < a->nc; ++p) {
    const PetscInt gap_row = a->d + p;
    if (gap_row < row_first || gap_row >= row_last || w[gap_row - row_first] == 0.0) continue;
    const PetscScalar weight = w[gap_row - row_first], a_weight = aw[gap_row - row_first];
    // The du row k of T gets gamma B_p[k] (a_p w_p, -w_p) in the columns of (30)_p and (31)_p.
    PetscErrorCode code = 0;
    PetscCall(VisitRow(j, gap_row, [&](PetscInt col, PetscScalar value) {
      if (col >= a->d || code != 0) return;
      const PetscInt targets[2] = {gap_row, a->d + a->nc + p};
      const PetscScalar values[2] = {gamma * a_weight * value, -gamma * weight * value};
      code = MatSetValues(a->t, 1, &col, 2, targets, values, ADD_VALUES);
    }));
    PetscCall(code);
  }
  PetscCall(VecRestoreArrayRead(a->weights, &w));
  PetscCall(VecRestoreArrayRead(a->scaled, &aw));
  PetscCall(MatAssemblyBegin(a->t, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(a->t, MAT_FINAL_ASSEMBLY));
  return 0;
}

// M^-1 = P^-1 T with P the field split of T J: J M^-1 = T^-1 (T J P^-1) T has the spectrum of the
// field split preconditioning T J.
PetscErrorCode SetUpAugmented(PC pc) {
  Augmented* a = nullptr;
  PetscCall(PCShellGetContext(pc, &a));
  ::Mat amat = nullptr, pmat = nullptr;
  PetscCall(PCGetOperators(pc, &amat, &pmat));
  PetscCall(MakeT(pmat, a));
  PetscCall(MatMatMult(a->t, pmat, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &a->tj));
  PetscCall(a->blocks->Expand(a->tj, &a->blocked_tj));
  PetscCall(MatDestroy(&a->tj));  // only its blocked copy is solved with
  PetscCall(PCSetOperators(a->inner, a->blocked_tj, a->blocked_tj));
  PetscCall(PCSetUp(a->inner));
  return 0;
}

PetscErrorCode ApplyAugmented(PC pc, ::Vec x, ::Vec y) {
  Augmented* a = nullptr;
  PetscCall(PCShellGetContext(pc, &a));
  PetscCall(MatMult(a->t, x, a->work));
  PetscCall(a->blocks->ToBlocked(a->work, a->blocked_in));
  PetscCall(PCApply(a->inner, a->blocked_in, a->blocked_out));
  PetscCall(a->blocks->ToReduced(a->blocked_out, y));
  return 0;
}

}  // namespace

PetscErrorCode SetAugmentedSplit(PC pc, const BodyContactModel& model, PetscInt first,
                                 PetscInt last) {
  PetscCall(DestroyAugmented(pc));
  auto* a = new Augmented;
  a->d = model.num_dofs();
  a->nc = model.num_pairs();
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(pc));
  PetscInt size = 0;
  PetscCallMPI(MPI_Allreduce(&last, &size, 1, MPIU_INT, MPI_MAX, comm));
  try {
    a->blocks = std::make_unique<NodeBlocks>(comm, model.body(), size, first, last);
  } catch (const std::exception&) {
    delete a;
    SETERRQ(comm, PETSC_ERR_LIB, "the node-blocked layout could not be made");
  }
  const char* prefix = nullptr;
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(PetscOptionsGetReal(nullptr, prefix, "-augmented_alpha", &a->alpha, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, prefix, "-augmented_cutoff", &a->cutoff, nullptr));
  PetscCall(PCCreate(comm, &a->inner));
  PetscCall(PCSetOptionsPrefix(a->inner, prefix));
  PetscCall(PCAppendOptionsPrefix(a->inner, "al_"));
  PetscCall(PCSetType(a->inner, PCFIELDSPLIT));
  PetscCall(PCSetFromOptions(a->inner));
  PetscCall(a->blocks->CreateBlockedVec(&a->blocked_in));
  PetscCall(VecDuplicate(a->blocked_in, &a->blocked_out));
  PetscCall(SetBlockedSplit(a->inner, *a->blocks, model.body().dim()));
  PetscCall(PCShellSetContext(pc, a));
  PetscCall(PCShellSetSetUp(pc, SetUpAugmented));
  PetscCall(PCShellSetApply(pc, ApplyAugmented));
  PetscCall(PCShellSetDestroy(pc, DestroyAugmented));
  PetscCall(PCShellSetName(pc, "augmented field split"));
  return 0;
}

}  // namespace cb
