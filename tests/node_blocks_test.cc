// The node-blocked system GAMG solves (formulations/petsc_dist/node_blocks.h): the rigid-body
// modes it hands PETSc are annihilated by the stiffness of a free body (K v = 0 is what makes them
// a near-null space), and the blocked matrix acts on the free rows as the step system's does.
#include <gtest/gtest.h>

#ifdef CONTACTBENCH_HAVE_PETSC
#include <petscmat.h>

#include <random>
#include <vector>

#include "core/sparse.h"
#include "formulations/petsc/petsc_adapter.h"
#include "formulations/petsc_dist/node_blocks.h"
#include "problems/box_mesh.h"

namespace cb {
namespace {

// The entries of a PETSc vector (one process) as an Eigen vector.
Vec ToEigen(::Vec v) {
  PetscInt n = 0;
  VecGetSize(v, &n);
  const PetscScalar* a = nullptr;
  VecGetArrayRead(v, &a);
  Vec out = Eigen::Map<const Vec>(a, n);
  VecRestoreArrayRead(v, &a);
  return out;
}

SolidHex8 Box(const std::vector<bool>& fixed = {}) {
  const BoxMesh mesh = MakeBoxMesh({{3, 2, 2}, {2.0, 1.5, 1.0}, {1.5, 1.0, 1.0}});
  return SolidHex8(mesh.coordinates, mesh.elements, SolidMaterial{1000.0, 0.3},
                   SolidKinematics::kSmallStrain, fixed);
}

TEST(NodeBlocksTest, TheRigidModesAreAnnihilatedByAFreeBodysStiffness) {
  StartPetsc();
  const SolidHex8 body = Box();
  SpMat k;
  body.Stiffness(Vec::Zero(body.num_dofs()), &k);
  const NodeBlocks blocks(PETSC_COMM_WORLD, body, body.num_dofs(), 0, body.num_dofs());
  MatNullSpace space = nullptr;
  ASSERT_EQ(blocks.RigidModes(&space), 0);
  PetscBool has_constant = PETSC_FALSE;
  PetscInt count = 0;
  const ::Vec* modes = nullptr;
  ASSERT_EQ(MatNullSpaceGetVecs(space, &has_constant, &count, &modes), 0);
  EXPECT_EQ(count, 6);  // three translations, three rotations
  const double k_norm = Eigen::MatrixXd(k).cwiseAbs().rowwise().sum().maxCoeff();
  std::vector<Vec> vs;
  for (PetscInt m = 0; m < count; ++m) {
    // No supports: blocked and step numbering agree (dof 3 node + c).
    const Vec v = ToEigen(modes[m]);
    EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    EXPECT_LT((k * v).cwiseAbs().maxCoeff(), 1e-12 * k_norm) << "mode " << m;
    vs.push_back(v);
  }
  // Independent: six orthonormal modes span the six rigid motions.
  for (std::size_t i = 0; i < vs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) EXPECT_NEAR(vs[i].dot(vs[j]), 0.0, 1e-12);
  }
  MatNullSpaceDestroy(&space);
}

// The step system: K, then `extra` rows coupled to a few du columns (as gap rows are), the
// coupled columns moved by `shift` so that two shifts give two patterns.
::Mat StepSystem(const SpMat& k, PetscInt extra, PetscInt shift) {
  const PetscInt d = k.rows(), size = d + extra;
  ::Mat reduced = nullptr;
  MatCreateSeqAIJ(PETSC_COMM_SELF, size, size, 96, nullptr, &reduced);  // K: 81 a row at most
  for (int col = 0; col < k.outerSize(); ++col) {
    for (SpMat::InnerIterator it(k, col); it; ++it) {
      MatSetValue(reduced, it.row(), it.col(), it.value(), INSERT_VALUES);
    }
  }
  for (PetscInt e = 0; e < extra; ++e) {
    const PetscInt coupled = 2 * e + 1 + shift;
    MatSetValue(reduced, d + e, coupled, 1.0 + e, INSERT_VALUES);
    MatSetValue(reduced, coupled, d + e, -0.5, INSERT_VALUES);
    MatSetValue(reduced, d + e, d + e, 3.0, INSERT_VALUES);
  }
  MatAssemblyBegin(reduced, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(reduced, MAT_FINAL_ASSEMBLY);
  return reduced;
}

// The largest difference between the step system's product with a random x and the blocked
// matrix's with x's blocked image, brought back, relative to the product's largest entry.
double ActionDifference(const NodeBlocks& blocks, ::Mat reduced, ::Mat blocked, ::Vec* by) {
  PetscInt size = 0;
  MatGetSize(reduced, &size, nullptr);
  ::Vec x = nullptr, y = nullptr, bx = nullptr, back = nullptr;
  MatCreateVecs(reduced, &x, &y);
  VecDuplicate(y, &back);
  blocks.CreateBlockedVec(&bx);
  VecDuplicate(bx, by);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (PetscInt i = 0; i < size; ++i) VecSetValue(x, i, uniform(rng), INSERT_VALUES);
  VecAssemblyBegin(x);
  VecAssemblyEnd(x);
  MatMult(reduced, x, y);
  blocks.ToBlocked(x, bx);
  MatMult(blocked, bx, *by);
  blocks.ToReduced(*by, back);
  const Vec expected = ToEigen(y), got = ToEigen(back);
  for (::Vec* v : {&x, &y, &bx, &back}) VecDestroy(v);
  return (expected - got).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
}

PetscReal StoredEntries(::Mat m) {
  MatInfo info;
  MatGetInfo(m, MAT_LOCAL, &info);
  return info.nz_used;
}

TEST(NodeBlocksTest, TheBlockedMatrixActsOnTheFreeRowsAsTheStepSystems) {
  StartPetsc();
  const SolidHex8 free_body = Box();
  std::vector<bool> fixed(static_cast<std::size_t>(3 * free_body.num_nodes()), false);
  for (int node = 0; node < free_body.num_nodes(); node += 5) fixed[3 * node + node % 3] = true;
  fixed[3 * 7] = fixed[3 * 7 + 1] = fixed[3 * 7 + 2] = true;  // a fully supported node
  const SolidHex8 body = Box(fixed);
  const PetscInt d = body.num_dofs(), extra = 4, size = d + extra;
  const PetscInt supported = 3 * body.num_nodes() - d;
  SpMat k;
  body.Stiffness(Vec::Zero(d), &k);
  const NodeBlocks blocks(PETSC_COMM_WORLD, body, size, 0, size);
  ::Mat blocked = nullptr;
  // Two step systems of different patterns expanded into the same blocked matrix, as at two
  // Newton iterations whose closed pairs differ: each time it acts as the system it came from
  // and holds that system's entries and the supported rows' alone.
  for (const PetscInt shift : {0, 6}) {
    ::Mat reduced = StepSystem(k, extra, shift);
    ASSERT_EQ(blocks.Expand(reduced, &blocked), 0);
    PetscInt rows = 0;
    MatGetSize(blocked, &rows, nullptr);
    EXPECT_EQ(rows, 3 * body.num_nodes() + extra);
    EXPECT_EQ(StoredEntries(blocked), StoredEntries(reduced) + static_cast<PetscReal>(supported))
        << "shift " << shift;
    ::Vec by = nullptr;
    EXPECT_LT(ActionDifference(blocks, reduced, blocked, &by), 1e-12) << "shift " << shift;
    // A supported row is an identity row: zero where x is zero-extended.
    EXPECT_EQ(ToEigen(by)[3 * 7], 0.0);
    // The blocked matrix holds each supported component's row alone on its diagonal.
    PetscScalar diagonal = 0.0;
    const PetscInt row = 3 * 7 + 1;
    MatGetValues(blocked, 1, &row, 1, &row, &diagonal);
    EXPECT_GT(diagonal, 0.0);
    VecDestroy(&by);
    MatDestroy(&reduced);
  }
  MatDestroy(&blocked);
}

}  // namespace
}  // namespace cb
#endif
