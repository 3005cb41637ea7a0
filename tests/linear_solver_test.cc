// Tests of src/solvers/linear_solver: every sparse linear solver behind the LinearSolver
// interface (analysis once per pattern, refactorisation, singular and non-finite matrices, the
// Jacobians of a contact step) and the factory.
#include "solvers/linear_solver.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/types.h"
#include "solver_test_support.h"
#include "solvers/equation_solver.h"

namespace cb {
namespace {

using ::cb::fixtures::ParamName;

// Random nonsymmetric matrix: a dominant-ish diagonal plus random entries within a band, the
// shape of a finite-element matrix rather than a random graph (whose LU fill is dense).
SpMat RandomSparseMatrix(int n, int per_column, int band, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> offset(-band, band);
  std::vector<Triplet> entries;
  for (int j = 0; j < n; ++j) {
    entries.emplace_back(j, j, 3.0 + value(rng));
    for (int k = 0; k < per_column; ++k) {
      const int i = j + offset(rng);
      if (i >= 0 && i < n && i != j) entries.emplace_back(i, j, value(rng));
    }
  }
  SpMat a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

class LinearSolverTest : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<LinearSolver> solver_ = MakeLinearSolver(GetParam());
};

TEST_P(LinearSolverTest, NameRoundTrips) { EXPECT_EQ(solver_->name(), GetParam()); }

TEST_P(LinearSolverTest, SolvesRandomNonsymmetricSystem) {
  const int n = 3000;
  const SpMat a = RandomSparseMatrix(n, 6, 60, 7);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Vec b(n);
  for (int i = 0; i < n; ++i) b[i] = value(rng);
  ASSERT_TRUE(solver_->Factorize(a)) << solver_->message();
  Vec x;
  ASSERT_TRUE(solver_->Solve(b, &x)) << solver_->message();
  EXPECT_LE((a * x - b).norm() / b.norm(), 1e-10);
  EXPECT_EQ(solver_->num_analyses(), 1);
}

TEST_P(LinearSolverTest, AnalysesPatternOnceAndAgainAfterAChange) {
  const int n = 200;
  const SpMat a = RandomSparseMatrix(n, 3, 10, 1);
  Vec b = Vec::LinSpaced(n, -1.0, 1.0);
  Vec x;
  for (int k = 0; k < 4; ++k) {
    const SpMat scaled = (1.0 + k) * a;
    ASSERT_TRUE(solver_->Factorize(scaled)) << solver_->message();
    ASSERT_TRUE(solver_->Solve(b, &x));
    EXPECT_LE((scaled * x - b).norm() / b.norm(), 1e-12);
  }
  EXPECT_EQ(solver_->num_analyses(), 1);

  // Same size and nnz count would not be enough: move one entry to another row.
  SpMat moved = a;
  std::vector<Triplet> entries;
  for (int j = 0; j < n; ++j) {
    for (SpMat::InnerIterator it(a, j); it; ++it) entries.emplace_back(it.row(), j, it.value());
  }
  entries.emplace_back(n - 1, 0, 0.5);  // a new entry far from the band
  moved.setFromTriplets(entries.begin(), entries.end());
  ASSERT_TRUE(solver_->Factorize(moved)) << solver_->message();
  ASSERT_TRUE(solver_->Solve(b, &x));
  EXPECT_LE((moved * x - b).norm() / b.norm(), 1e-12);
  EXPECT_EQ(solver_->num_analyses(), 2);
  ASSERT_TRUE(solver_->Factorize(2.0 * moved));
  EXPECT_EQ(solver_->num_analyses(), 2);
  ASSERT_TRUE(solver_->Factorize(a));
  ASSERT_TRUE(solver_->Solve(b, &x));
  EXPECT_LE((a * x - b).norm() / b.norm(), 1e-12);
  EXPECT_EQ(solver_->num_analyses(), 3);
}

TEST_P(LinearSolverTest, SingularMatrixReturnsFalseWithMessage) {
  // Rows 0 and 1 are dependent; the factorisation meets an exactly zero pivot.
  const std::vector<Triplet> entries = {
      {0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 2.0}, {1, 1, 4.0}, {2, 2, 1.0}};
  SpMat a(3, 3);
  a.setFromTriplets(entries.begin(), entries.end());
  bool ok = true;
  EXPECT_NO_THROW(ok = solver_->Factorize(a));
  EXPECT_FALSE(ok);
  EXPECT_FALSE(solver_->message().empty());
  Vec x;
  EXPECT_FALSE(solver_->Solve(Vec::Ones(3), &x));

  // A structurally empty column.
  SpMat empty_column(3, 3);
  empty_column.insert(0, 0) = 1.0;
  empty_column.insert(1, 0) = 1.0;
  empty_column.insert(2, 2) = 1.0;
  empty_column.makeCompressed();
  EXPECT_FALSE(solver_->Factorize(empty_column));
  EXPECT_FALSE(solver_->message().empty());
}

TEST_P(LinearSolverTest, RecoversAfterASingularMatrixWithoutReanalysis) {
  const std::vector<Triplet> singular = {
      {0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 2.0}, {1, 1, 4.0}, {2, 2, 1.0}};
  std::vector<Triplet> regular = singular;
  regular[3] = Triplet(1, 1, 5.0);
  SpMat a(3, 3), b(3, 3);
  a.setFromTriplets(singular.begin(), singular.end());
  b.setFromTriplets(regular.begin(), regular.end());
  EXPECT_FALSE(solver_->Factorize(a));
  ASSERT_TRUE(solver_->Factorize(b)) << solver_->message();
  Vec x;
  ASSERT_TRUE(solver_->Solve(Vec::Ones(3), &x));
  EXPECT_LE((b * x - Vec::Ones(3)).norm(), 1e-14);
  EXPECT_EQ(solver_->num_analyses(), 1);
}

TEST_P(LinearSolverTest, NonFiniteEntriesAreRejected) {
  SpMat a = RandomSparseMatrix(20, 2, 3, 5);
  a.valuePtr()[7] = std::nan("");
  EXPECT_FALSE(solver_->Factorize(a));
  EXPECT_NE(solver_->message().find("non-finite"), std::string::npos) << solver_->message();
  a.valuePtr()[7] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(solver_->Factorize(a));
}

TEST_P(LinearSolverTest, NonSquareMatrixThrows) {
  SpMat a(3, 4);
  a.insert(0, 0) = 1.0;
  EXPECT_THROW(solver_->Factorize(a), std::invalid_argument);
}

TEST_P(LinearSolverTest, SolveWithoutFactorisationFails) {
  Vec x;
  EXPECT_FALSE(solver_->Solve(Vec::Ones(3), &x));
  EXPECT_FALSE(solver_->message().empty());
}

TEST_P(LinearSolverTest, AcceptsUncompressedMatrixAndAliasedRightHandSide) {
  SpMat a(3, 3);
  a.insert(0, 0) = 2.0;
  a.insert(1, 1) = 4.0;
  a.insert(2, 2) = 8.0;
  a.insert(0, 2) = 1.0;
  ASSERT_FALSE(a.isCompressed());
  ASSERT_TRUE(solver_->Factorize(a)) << solver_->message();
  Vec x = Vec::Ones(3);
  const Vec b = x;
  ASSERT_TRUE(solver_->Solve(x, &x));
  EXPECT_LE((a * x - b).norm(), 1e-14);
}

// Same pattern, changing values, and pivots that the values turn bad: a well-conditioned random
// part with a 2 x 2 block in the last rows and columns (coupled one way to the rest, so that
// BTF orders keep it a block of its own). Every matrix is well conditioned; what changes is
// which pivots are safe. A solver that reuses its last pivot order (klu) must notice when that
// order fails and pivot afresh.
TEST_P(LinearSolverTest, SamePatternWithPivotsThatTurnBad) {
  const int m = 60;
  const SpMat random_part = RandomSparseMatrix(m, 3, 8, 17);
  struct Block {
    double a00, a01, a10, a11;
    const char* what;
  };
  const std::vector<Block> blocks = {
      {2.0, 1.0, 1.0, 2.0, "diagonally dominant: any LU pivots on the diagonal"},
      {3.0, 1.0, 1.0, 3.0, "new values, the diagonal still safe: the old order is reused"},
      {0.0, 1.0, 1.0, 0.0, "a permutation: the old diagonal pivot is exactly zero"},
      {1.0, 1e-14, 1e-14, 1.0, "near identity: the old off-diagonal pivot is 1e-14"},
      {4.0, 1.0, 2.0, 3.0, "dominant diagonal again: the order from the identity is reused"},
  };
  Vec x;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Block& blk = blocks[k];
    std::vector<Triplet> entries;
    for (int j = 0; j < m; ++j) {
      for (SpMat::InnerIterator it(random_part, j); it; ++it) {
        entries.emplace_back(it.row(), j, (1.0 + 0.1 * k) * it.value());
      }
    }
    entries.emplace_back(m, m, blk.a00);  // stored even when zero: the pattern stays the same
    entries.emplace_back(m, m + 1, blk.a01);
    entries.emplace_back(m + 1, m, blk.a10);
    entries.emplace_back(m + 1, m + 1, blk.a11);
    entries.emplace_back(3, m, 0.5);  // the random part depends on the block, not conversely
    entries.emplace_back(m / 2, m + 1, -0.25);
    SpMat a(m + 2, m + 2);
    a.setFromTriplets(entries.begin(), entries.end());
    ASSERT_EQ(a.nonZeros(), random_part.nonZeros() + 6);

    const Vec b = Vec::LinSpaced(m + 2, -1.0, 2.0);
    ASSERT_TRUE(solver_->Factorize(a)) << k << " (" << blk.what << "): " << solver_->message();
    ASSERT_TRUE(solver_->Solve(b, &x)) << k << ": " << solver_->message();
    EXPECT_LE((a * x - b).norm() / b.norm(), 1e-10) << k << " (" << blk.what << ")";
  }
  EXPECT_EQ(solver_->num_analyses(), 1);
  // klu: full factorisations for the first matrix and for the two whose old pivot failed (a
  // zero pivot; then growth 1e14); the other two reuse the order.
  // cholmod: no structure given, so the same through its fallback, klu.
  const bool reuses = GetParam() == "klu" || GetParam() == "cholmod";
  EXPECT_EQ(solver_->num_full_factorizations(), reuses ? 3 : 5);
}

TEST_P(LinearSolverTest, CountsFullFactorisations) {
  const SpMat a = RandomSparseMatrix(100, 3, 10, 3);
  const Vec b = Vec::Ones(100);
  Vec x;
  EXPECT_EQ(solver_->num_full_factorizations(), 0);
  for (int k = 0; k < 4; ++k) {
    const SpMat scaled = (1.0 + 0.5 * k) * a;
    ASSERT_TRUE(solver_->Factorize(scaled)) << solver_->message();
    ASSERT_TRUE(solver_->Solve(b, &x));
    EXPECT_LE((scaled * x - b).norm() / b.norm(), 1e-12);
  }
  // cholmod: these matrices have no block structure, so its fallback (klu) factorises them.
  const bool reuses = GetParam() == "klu" || GetParam() == "cholmod";
  EXPECT_EQ(solver_->num_full_factorizations(), reuses ? 1 : 4);
  // A new pattern: analysed, so factorised afresh.
  ASSERT_TRUE(solver_->Factorize(RandomSparseMatrix(100, 3, 10, 4))) << solver_->message();
  EXPECT_EQ(solver_->num_analyses(), 2);
  EXPECT_EQ(solver_->num_full_factorizations(), reuses ? 2 : 5);
  // A non-finite matrix is rejected before any factorisation.
  SpMat bad = RandomSparseMatrix(100, 3, 10, 4);
  bad.valuePtr()[0] = std::nan("");
  EXPECT_FALSE(solver_->Factorize(bad));
  EXPECT_EQ(solver_->num_full_factorizations(), reuses ? 2 : 5);
}

// A singular matrix with the pattern of a factorised one (klu: the refactorisation meets the
// zero pivot, and so does the full factorisation it falls back to), then a regular one again.
TEST_P(LinearSolverTest, SingularMatrixBetweenRegularOnesWithThePattern) {
  const std::vector<Triplet> regular = {{0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 2.0},
                                        {1, 1, 5.0}, {2, 2, 1.0}, {0, 2, 1.0}};
  std::vector<Triplet> singular = regular;
  singular[3] = Triplet(1, 1, 4.0);  // rows 0 and 1 of the leading 2 x 2 block dependent
  singular[5] = Triplet(0, 2, 0.0);
  SpMat a(3, 3), s(3, 3);
  a.setFromTriplets(regular.begin(), regular.end());
  s.setFromTriplets(singular.begin(), singular.end());
  const Vec b = Vec::Ones(3);
  Vec x;
  ASSERT_TRUE(solver_->Factorize(a)) << solver_->message();
  EXPECT_FALSE(solver_->Factorize(s));
  EXPECT_FALSE(solver_->message().empty());
  EXPECT_FALSE(solver_->Solve(b, &x));
  ASSERT_TRUE(solver_->Factorize(2.0 * a)) << solver_->message();
  ASSERT_TRUE(solver_->Solve(b, &x)) << solver_->message();
  EXPECT_LE((2.0 * a * x - b).norm(), 1e-14);
  EXPECT_EQ(solver_->num_analyses(), 1);
}

// The Jacobian shape of the implicit FB formulation for a plane-stress block held only by
// frictionless contact on two edges (as the "block" problem): unknowns (u, g, r, dlambda, rho)
// and rows
//   F1 = K u / R - G^T r - f dlambda,   F2 = g + G u / L,
//   F3 = dpsi/dg g + dpsi/dr r + dpsi/drho rho,   F4 = the eta row in (g^T r / nc, rho),
//   F5 = dlambda (a fixed-load step).
// K alone is singular (the body floats) and F5 is a row singleton off the diagonal. `state`
// changes the values only: 0 is a cold start (g = r = 0), others open and close some contacts.
// With UMFPACK's default controls this matrix (m = 50) was solved to relative residuals of 3e-2
// to 20, as the block problem's Jacobians were (see UmfpackSolver).
SpMat ContactBlockJacobian(int m, int state) {
  // Q4 plane-stress element stiffness for a unit square, nu = 0.3, E t scaled so that K / R is
  // O(1e4) as in the block problem; 2 x 2 Gauss points.
  const double nu = 0.3;
  const double k = 1e4 / (1.0 - nu * nu);
  const double d[3][3] = {{k, k * nu, 0.0}, {k * nu, k, 0.0}, {0.0, 0.0, k * (1 - nu) / 2}};
  const double xi[4] = {-1, 1, 1, -1};
  const double eta[4] = {-1, -1, 1, 1};
  double ke[8][8] = {};
  const double gauss = 1.0 / std::sqrt(3.0);
  for (double s : {-gauss, gauss}) {
    for (double t : {-gauss, gauss}) {
      double bm[3][8] = {};
      for (int c = 0; c < 4; ++c) {  // corner c: dN_c/dx and dN_c/dy on a unit square
        const double dx = 0.5 * xi[c] * (1 + eta[c] * t);
        const double dy = 0.5 * eta[c] * (1 + xi[c] * s);
        bm[0][2 * c] = dx;
        bm[1][2 * c + 1] = dy;
        bm[2][2 * c] = dy;
        bm[2][2 * c + 1] = dx;
      }
      for (int p = 0; p < 8; ++p) {
        for (int q = 0; q < 8; ++q) {
          double v = 0.0;
          for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) v += bm[i][p] * d[i][j] * bm[j][q];
          }
          ke[p][q] += 0.25 * v;  // Gauss weight 1, det J = 1/4
        }
      }
    }
  }
  const auto node = [m](int i, int j) { return j * (m + 1) + i; };
  const int dofs = 2 * (m + 1) * (m + 1);
  std::vector<Triplet> e;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      const int nodes[4] = {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)};
      for (int p = 0; p < 8; ++p) {
        for (int q = 0; q < 8; ++q) {
          e.emplace_back(2 * nodes[p / 2] + p % 2, 2 * nodes[q / 2] + q % 2, ke[p][q]);
        }
      }
    }
  }
  // Contacts: x of the left edge against a wall, y of the bottom edge against a floor.
  std::vector<int> contact_dof;
  for (int j = 0; j <= m; ++j) contact_dof.push_back(2 * node(0, j));
  for (int i = 0; i <= m; ++i) contact_dof.push_back(2 * node(i, 0) + 1);
  const int nc = static_cast<int>(contact_dof.size());
  const int g = dofs, r = dofs + nc, dlambda = dofs + 2 * nc, rho = dlambda + 1;
  const int n = rho + 1;
  const double rho_value = state == 0 ? 1e-1 : 1e-3 / state;
  for (int p = 0; p < nc; ++p) {
    // Cold start: g = r = 0. Otherwise a third of the pairs open (g > 0, r = 0), the rest
    // closed (g = 0, r > 0), with psi's derivatives at (g, -r, rho).
    const bool open = state != 0 && (7 * p + state) % 3 == 0;
    const double gp = state == 0 ? 0.0 : (open ? 0.5 : 0.0);
    const double rp = state == 0 ? 0.0 : (open ? 0.0 : 1.0 + 0.1 * state);
    const double sq = std::sqrt(gp * gp + rp * rp + 2 * rho_value * rho_value);
    e.emplace_back(contact_dof[p], r + p, 1.0);        // F1: -grad phi^T r with phi = -u
    e.emplace_back(dofs + p, contact_dof[p], -100.0);  // F2: phi / L with L = 1e-2
    e.emplace_back(dofs + p, g + p, 1.0);
    e.emplace_back(dofs + nc + p, g + p, gp / sq - 1.0);  // F3 = psi(g, -r, rho)
    e.emplace_back(dofs + nc + p, r + p, 1.0 + rp / sq);
    e.emplace_back(dofs + nc + p, rho, 2.0 * rho_value / sq);
    e.emplace_back(dlambda, g + p, -rp / nc);  // F4: -m - (exp(rho) - 1), m = g^T r / nc
    e.emplace_back(dlambda, r + p, -gp / nc);
  }
  e.emplace_back(dlambda, rho, -std::exp(rho_value));
  for (int j = 0; j <= m; ++j) {  // load on the right edge
    e.emplace_back(2 * node(m, j), dlambda, -0.5);
    e.emplace_back(2 * node(m, j) + 1, dlambda, -0.5);
  }
  e.emplace_back(rho, dlambda, 1.0);  // F5: the fixed-load row
  SpMat a(n, n);
  a.setFromTriplets(e.begin(), e.end());
  return a;
}

TEST_P(LinearSolverTest, SolvesAContactJacobianSequenceAccurately) {
  Vec x;
  for (int state = 0; state < 4; ++state) {
    const SpMat a = ContactBlockJacobian(50, state);
    const Vec b = Vec::LinSpaced(a.rows(), -1.0, 1.0);
    ASSERT_TRUE(solver_->Factorize(a)) << state << ": " << solver_->message();
    ASSERT_TRUE(solver_->Solve(b, &x)) << state << ": " << solver_->message();
    EXPECT_LE((a * x - b).norm() / b.norm(), 1e-10) << "state " << state;
  }
  EXPECT_EQ(solver_->num_analyses(), 1);
}

INSTANTIATE_TEST_SUITE_P(AllLinearSolvers, LinearSolverTest,
                         ::testing::ValuesIn(LinearSolverNames()), ParamName);

TEST(LinearSolverFactoryTest, DefaultComesFirstAndUnknownNameListsValidOnes) {
  ASSERT_FALSE(LinearSolverNames().empty());
  EXPECT_EQ(LinearSolverNames().front(), DefaultLinearSolverName());
  EXPECT_EQ(SolverOptions().linear_solver, DefaultLinearSolverName());
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  EXPECT_EQ(LinearSolverNames().size(), 4u);
  EXPECT_EQ(DefaultLinearSolverName(), "cholmod");
#else
  EXPECT_EQ(DefaultLinearSolverName(), "sparse-lu");
#endif
  try {
    MakeLinearSolver("cholesky");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    for (const std::string& name : LinearSolverNames()) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

// A factorisation that runs out of memory says so, with the size, and is not called singular
// (it once read "singular Jacobian ... KLU status -2"). In a child process whose address space is
// capped a little above what it already uses, klu factorises the 5-point Laplacian of a 400 x 400
// grid (160 000 unknowns, fill of order 1e7 entries, far past the cap).
TEST(LinearSolverFailureTest, OutOfMemoryIsReportedAsSuch) {
#if defined(__has_feature)
#if __has_feature(address_sanitizer)  // clang's word for it; gcc defines __SANITIZE_ADDRESS__
#define CB_UNDER_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(CB_UNDER_ADDRESS_SANITIZER)
  GTEST_SKIP() << "under AddressSanitizer, whose shadow memory cannot be mapped under the cap";
#endif
  const std::vector<std::string> names = LinearSolverNames();
  if (std::find(names.begin(), names.end(), "klu") == names.end()) GTEST_SKIP() << "no klu";
  const int side = 400, n = side * side;
  std::vector<Triplet> entries;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int k = i * side + j;
      entries.emplace_back(k, k, 4.0);
      if (i > 0) entries.emplace_back(k, k - side, -1.0);
      if (i + 1 < side) entries.emplace_back(k, k + side, -1.0);
      if (j > 0) entries.emplace_back(k, k - 1, -1.0);
      if (j + 1 < side) entries.emplace_back(k, k + 1, -1.0);
    }
  }
  SpMat a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  const auto factorise_capped = [&a] {
    std::unique_ptr<LinearSolver> klu = MakeLinearSolver("klu");
    std::ifstream status("/proc/self/status");
    std::string line;
    long used_kb = 0;
    while (std::getline(status, line)) {
      if (line.rfind("VmSize:", 0) == 0) used_kb = std::stol(line.substr(7));
    }
    const rlim_t cap = static_cast<rlim_t>(used_kb + 16 * 1024) * 1024;
    const rlimit limit{cap, cap};
    if (used_kb == 0 || setrlimit(RLIMIT_AS, &limit) != 0) std::_Exit(3);
    try {
      const bool ok = klu->Factorize(a);
      const bool named =
          klu->message().find("out of memory factorising a 160000 x 160000") != std::string::npos;
      std::_Exit(!ok && named && !klu->singular() ? 0 : 1);
    } catch (const std::bad_alloc&) {
      std::_Exit(2);  // our own allocation, not KLU's, ran out first
    }
  };
  EXPECT_EXIT(factorise_capped(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace cb
