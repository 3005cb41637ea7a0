// Tests of src/solvers/condensed_cholesky: the "cholmod" solver on Jacobians of the block form
// (both ways of factorising Kc against the full LU) and its fallbacks to the LU.
#include "solvers/condensed_cholesky.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "core/abandonable_work.h"
#include "core/slow_work.h"
#include "core/types.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {
namespace {

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
// A Jacobian with the block form of JacobianStructure: A symmetric positive definite (a chain
// with 2 dofs per node), pairs on `nc` distinct dofs (two entries each), E = I,
// Da <= 0 <= Db with every fourth pair closed (Db = 0, as the nonsmooth rows) and every fourth
// open (Da = 0), and two border columns / rows like (dlambda, rho) with the eta and arc-length
// rows. `spread` places the pairs every `spread` dofs.
SpMat StructuredJacobian(int d, int nc, int spread, double coupling, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  const int n = d + 2 * nc + 2;
  std::vector<Triplet> e;
  for (int j = 0; j < d; ++j) {
    e.emplace_back(j, j, 4.0 + u(rng));
    if (j + 1 < d) {
      const double v = -u(rng);
      e.emplace_back(j + 1, j, v);
      e.emplace_back(j, j + 1, v);
    }
    if (j + 2 < d) {
      const double v = 0.5 * u(rng);
      e.emplace_back(j + 2, j, v);
      e.emplace_back(j, j + 2, v);
    }
  }
  const int dl = d + 2 * nc, rho = dl + 1;
  for (int p = 0; p < nc; ++p) {
    const int dof = (p * spread) % (d - 1);
    const double g0 = u(rng), g1 = u(rng) - 0.6;
    e.emplace_back(d + p, dof, g0);  // R2: G
    e.emplace_back(d + p, dof + 1, g1);
    e.emplace_back(dof, d + nc + p, -coupling * g0);  // R1: H = -coupling G^T
    e.emplace_back(dof + 1, d + nc + p, -coupling * g1);
    e.emplace_back(d + p, d + p, 1.0);  // E
    const double da = p % 4 == 2 ? 0.0 : -u(rng);
    const double db = p % 4 == 0 ? 0.0 : u(rng);
    e.emplace_back(d + nc + p, d + p, da);
    e.emplace_back(d + nc + p, d + nc + p, db);
    e.emplace_back(d + nc + p, rho, 0.1 * u(rng));  // U3
    e.emplace_back(dl, d + p, -0.01 * u(rng));      // eta row: Vg, Vr
    e.emplace_back(dl, d + nc + p, -0.01 * u(rng));
  }
  e.emplace_back(dl, rho, -1.0 - u(rng));  // W
  for (int j = 0; j < d; ++j) {
    if (j % 3 == 0) e.emplace_back(j, dl, -0.3 * u(rng));  // U1: the load column
    e.emplace_back(rho, j, 0.01 * (u(rng) - 0.5));         // arc-length row: V
  }
  e.emplace_back(rho, dl, 0.5);
  SpMat a(n, n);
  a.setFromTriplets(e.begin(), e.end());
  a.makeCompressed();
  return a;
}

void ExpectCondensedMatchesLu(int d, int nc, int spread, bool contact_block) {
  const double coupling = 0.3;
  const JacobianStructure structure{d, nc, coupling};
  auto cholmod = MakeLinearSolver("cholmod");
  auto lu = MakeLinearSolver("klu");
  cholmod->SetStructure(&structure);
  for (unsigned seed = 1; seed <= 3; ++seed) {
    SpMat a = StructuredJacobian(d, nc, spread, coupling, seed);
    if (seed > 1) {
      // Same stiffness as the first matrix (so the contact-block factor is reused), new pairs.
      const SpMat first = StructuredJacobian(d, nc, spread, coupling, 1);
      for (int j = 0; j < d; ++j) {
        for (int k = a.outerIndexPtr()[j]; k < a.outerIndexPtr()[j + 1]; ++k) {
          if (a.innerIndexPtr()[k] < d) a.valuePtr()[k] = first.valuePtr()[k];
        }
      }
    }
    const Vec b = Vec::LinSpaced(a.rows(), -1.0, 2.0);
    Vec x, x_lu;
    ASSERT_TRUE(lu->Factorize(a)) << "seed " << seed << ": " << lu->message();
    ASSERT_TRUE(lu->Solve(b, &x_lu));
    ASSERT_TRUE(cholmod->Factorize(a)) << cholmod->message();
    ASSERT_TRUE(cholmod->Solve(b, &x)) << cholmod->message();
    EXPECT_LE((x - x_lu).norm() / x_lu.norm(), 1e-11) << "seed " << seed;
    EXPECT_LE((a * x - b).norm() / b.norm(), 1e-12) << "seed " << seed;
  }
  const CondensedSolverStats* stats = CondensedStats(*cholmod);
  ASSERT_NE(stats, nullptr);
  EXPECT_EQ(stats->condensed_factorizations, 3);
  EXPECT_EQ(stats->contact_block_factorizations, contact_block ? 3 : 0);
  EXPECT_EQ(stats->fallback_factorizations, 0);
  EXPECT_EQ(stats->fallback_solves, 0);
  EXPECT_GT(stats->capped_pairs, 0);  // the closed pairs (Db = 0)
  EXPECT_GT(stats->refinement_sweeps, 0);
}

// ||a x - b|| / ||b|| for the x that `solver` gives after factorising `a`; infinity (and a test
// failure) when the factorisation or the solve fails.
double SolveResidual(LinearSolver& solver, const SpMat& a, const Vec& b) {
  Vec x;
  if (!solver.Factorize(a) || !solver.Solve(b, &x)) {
    ADD_FAILURE() << solver.name() << ": " << solver.message();
    return std::numeric_limits<double>::infinity();
  }
  return (a * x - b).norm() / b.norm();
}

TEST(CondensedCholeskyTest, WholeCondensedMatrixPathMatchesTheFullLu) {
  // Many contact dofs (400 of 1200): Kc factorised whole by CHOLMOD.
  ExpectCondensedMatchesLu(1200, 200, 5, false);
}

TEST(CondensedCholeskyTest, ContactBlockPathMatchesTheFullLu) {
  // d >= 1000 with few contact dofs: only the dense contact block is refactorised.
  ExpectCondensedMatchesLu(1500, 60, 11, true);
}

TEST(CondensedCholeskyTest, SmallSystemsGoToTheLu) {
  const int d = 300, nc = 40;
  const JacobianStructure structure{d, nc, 0.3};
  auto cholmod = MakeLinearSolver("cholmod");
  cholmod->SetStructure(&structure);
  const SpMat a = StructuredJacobian(d, nc, 7, 0.3, 5);
  const Vec b = Vec::LinSpaced(a.rows(), -1.0, 2.0);
  EXPECT_LE(SolveResidual(*cholmod, a, b), 1e-12);
  EXPECT_EQ(CondensedStats(*cholmod)->fallback_factorizations, 1);
  EXPECT_EQ(CondensedStats(*cholmod)->condensed_factorizations, 0);
}

TEST(CondensedCholeskyTest, FallsBackWhereTheStructureDoesNotHold) {
  const int d = 1200, nc = 40;
  const JacobianStructure structure{d, nc, 0.3};
  auto cholmod = MakeLinearSolver("cholmod");
  cholmod->SetStructure(&structure);
  // H is not -coupling G^T here (the structure claims 0.3, the matrix has 0.7).
  const SpMat a = StructuredJacobian(d, nc, 7, 0.7, 5);
  const Vec b = Vec::LinSpaced(a.rows(), -1.0, 2.0);
  EXPECT_LE(SolveResidual(*cholmod, a, b), 1e-12);
  EXPECT_EQ(CondensedStats(*cholmod)->fallback_factorizations, 1);
  // Without a structure: the fallback, with the same answer.
  cholmod->SetStructure(nullptr);
  EXPECT_LE(SolveResidual(*cholmod, a, b), 1e-12);
  EXPECT_EQ(CondensedStats(*cholmod)->fallback_factorizations, 2);
}

TEST(CondensedCholeskyTest, IndefiniteStiffnessIsStillSolvedExactly) {
  // An indefinite Kc: CHOLMOD's simplicial LDL^T (chosen for sparse enough factors) may
  // factorise it without pivoting, a supernodal LL^T refuses it and the LU takes over; either
  // way the refinement on the full system keeps the answer exact.
  for (int d : {1200, 1500}) {
    const int nc = 40;
    const JacobianStructure structure{d, nc, 0.3};
    auto cholmod = MakeLinearSolver("cholmod");
    cholmod->SetStructure(&structure);
    SpMat a = StructuredJacobian(d, nc, 7, 0.3, 6);
    a.coeffRef(d / 2, d / 2) = -10.0;
    const Vec b = Vec::LinSpaced(a.rows(), -1.0, 2.0);
    EXPECT_LE(SolveResidual(*cholmod, a, b), 1e-12) << "d = " << d;
  }
}
#endif

// A fall-back factorisation of a large matrix is reported before it starts (core/slow_work.h),
// for the progress line to say so; one of a small matrix is not.
std::vector<SlowWork> g_reported;

TEST(CondensedCholeskyTest, ALargeFallbackIsReportedBeforeItStarts) {
  SetSlowWorkListener([](const SlowWork& work) { g_reported.push_back(work); });
  const auto banded = [](int n) {
    // Diagonally dominant, 21 entries a column: the LU (without structure) factorises it.
    std::vector<Eigen::Triplet<double>> e;
    for (int j = 0; j < n; ++j) {
      for (int i = std::max(0, j - 10); i <= std::min(n - 1, j + 10); ++i) {
        e.emplace_back(i, j, i == j ? 30.0 : -1.0);
      }
    }
    SpMat a(n, n);
    a.setFromTriplets(e.begin(), e.end());
    a.makeCompressed();
    return a;
  };
  auto cholmod = MakeLinearSolver("cholmod");
  g_reported.clear();
  const SpMat small = banded(1000);
  ASSERT_TRUE(cholmod->Factorize(small)) << cholmod->message();
  EXPECT_TRUE(g_reported.empty());
  const SpMat large = banded(12000);
  ASSERT_GE(large.nonZeros(), kAbandonableMinNonZeros);
  ASSERT_TRUE(cholmod->Factorize(large)) << cholmod->message();
  SetSlowWorkListener(nullptr);
  ASSERT_EQ(g_reported.size(), 1u);
  EXPECT_EQ(g_reported[0].from, "cholmod");
  EXPECT_EQ(g_reported[0].to, "klu");
  EXPECT_EQ(g_reported[0].rows, 12000);
  EXPECT_EQ(g_reported[0].nonzeros, large.nonZeros());
}

}  // namespace
}  // namespace cb
