#include "formulations/petsc_dist/field_split.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

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
  // PCFIELDSPLIT hands a split's "nearnullspace" to the split's matrix (for GAMG).
  PetscCall(PetscObjectCompose(reinterpret_cast<PetscObject>(du), "nearnullspace",
                               reinterpret_cast<PetscObject>(rigid)));
  PetscCall(MatNullSpaceDestroy(&rigid));
  PetscCall(PCFieldSplitSetIS(pc, "0", du));
  PetscCall(PCFieldSplitSetIS(pc, "1", rest));
  PetscCall(ISDestroy(&du));
  PetscCall(ISDestroy(&rest));
  return 0;
}

}  // namespace cb
