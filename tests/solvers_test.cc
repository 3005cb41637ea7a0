// Tests of src/solvers: the sparse linear-solver wrappers and the three equation solvers on
// small systems with known solutions.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/types.h"
#include "solvers/condensed_cholesky.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {
namespace {

// ----------------------------------------------------------------------------------------------
// Test systems with known solutions.

double InfNorm(const Vec& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

// F(x) = A x - b with a nonsymmetric tridiagonal A and b = A x*: one Newton step is exact.
class LinearTestSystem : public EquationSystem {
 public:
  explicit LinearTestSystem(int n) : a_(n, n), solution_(n) {
    std::vector<Triplet> entries;
    for (int i = 0; i < n; ++i) {
      entries.emplace_back(i, i, 4.0 + 0.01 * i);
      if (i > 0) entries.emplace_back(i, i - 1, -1.0);
      if (i + 1 < n) entries.emplace_back(i, i + 1, -2.0);
      solution_[i] = std::sin(1.0 + i);
    }
    a_.setFromTriplets(entries.begin(), entries.end());
    b_ = a_ * solution_;
  }
  int size() const override { return static_cast<int>(a_.rows()); }
  bool Residual(const Vec& x, Vec* f) override {
    *f = a_ * x - b_;
    return true;
  }
  void Jacobian(const Vec&, SpMat* j) override { *j = a_; }
  const Vec& solution() const { return solution_; }

 private:
  SpMat a_;
  Vec b_, solution_;
};

// Rosenbrock's function as equations: F = (10 (x2 - x1^2), 1 - x1), root (1, 1).
class RosenbrockSystem : public EquationSystem {
 public:
  int size() const override { return 2; }
  bool Residual(const Vec& x, Vec* f) override {
    f->resize(2);
    (*f)[0] = 10.0 * (x[1] - x[0] * x[0]);
    (*f)[1] = 1.0 - x[0];
    return true;
  }
  void Jacobian(const Vec& x, SpMat* j) override {
    const std::vector<Triplet> entries = {{0, 0, -20.0 * x[0]}, {0, 1, 10.0}, {1, 0, -1.0}};
    j->resize(2, 2);
    j->setFromTriplets(entries.begin(), entries.end());
  }
  static Vec Start() { return Vec{{-1.2, 1.0}}; }
  static Vec Solution() { return Vec{{1.0, 1.0}}; }
};

// Powell's badly scaled function: F = (1e4 x1 x2 - 1, exp(-x1) + exp(-x2) - 1.0001).
class PowellBadlyScaledSystem : public EquationSystem {
 public:
  int size() const override { return 2; }
  bool Residual(const Vec& x, Vec* f) override {
    f->resize(2);
    (*f)[0] = 1e4 * x[0] * x[1] - 1.0;
    (*f)[1] = std::exp(-x[0]) + std::exp(-x[1]) - 1.0001;
    return true;
  }
  void Jacobian(const Vec& x, SpMat* j) override {
    const std::vector<Triplet> entries = {
        {0, 0, 1e4 * x[1]}, {0, 1, 1e4 * x[0]}, {1, 0, -std::exp(-x[0])}, {1, 1, -std::exp(-x[1])}};
    j->resize(2, 2);
    j->setFromTriplets(entries.begin(), entries.end());
  }
  static Vec Start() { return Vec{{0.0, 1.0}}; }
  // x1 x2 = 1e-4 exactly, so x2 solves exp(-1e-4 / x2) + exp(-x2) = 1.0001 (decreasing on
  // [1, 20]); bisection to rounding.
  static Vec Solution() {
    auto g = [](double x2) { return std::exp(-1e-4 / x2) + std::exp(-x2) - 1.0001; };
    double lo = 1.0, hi = 20.0;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (g(mid) > 0.0 ? lo : hi) = mid;
    }
    const double x2 = 0.5 * (lo + hi);
    return Vec{{1e-4 / x2, x2}};
  }
};

// The discretised Bratu problem -u'' = lambda exp(u) on (0, 1), u(0) = u(1) = 0, with n
// interior nodes, made to have a known discrete solution: the right-hand side r is chosen so
// that the nodal values of the exact continuous solution
//   u(t) = -2 log(cosh((t - 1/2) theta / 2) / cosh(theta / 4)),  theta = sqrt(2 lambda) cosh(theta
//   / 4)
// solve the discrete equations exactly. r is O(h^2) (the discretisation error), so this is
// Bratu's problem up to a small perturbation.
class BratuSystem : public EquationSystem {
 public:
  BratuSystem(int n, double lambda) : n_(n), lambda_(lambda), solution_(n), r_(n) {
    double theta = 1.0;  // fixed point on the lower branch; the map is a contraction there
    for (int i = 0; i < 200; ++i) theta = std::sqrt(2.0 * lambda) * std::cosh(theta / 4.0);
    h_ = 1.0 / (n + 1);
    for (int i = 0; i < n; ++i) {
      const double t = (i + 1) * h_;
      solution_[i] = -2.0 * std::log(std::cosh((t - 0.5) * theta / 2.0) / std::cosh(theta / 4.0));
    }
    r_.setZero();
    Vec f(n);
    Residual(solution_, &f);
    r_ = f;
  }
  int size() const override { return n_; }
  bool Residual(const Vec& u, Vec* f) override {
    f->resize(n_);
    const double inv_h2 = 1.0 / (h_ * h_);
    for (int i = 0; i < n_; ++i) {
      const double left = i > 0 ? u[i - 1] : 0.0;
      const double right = i + 1 < n_ ? u[i + 1] : 0.0;
      (*f)[i] = (2.0 * u[i] - left - right) * inv_h2 - lambda_ * std::exp(u[i]) - r_[i];
    }
    return true;
  }
  // Fills the values in place once the pattern exists, as a model with a fixed pattern would.
  void Jacobian(const Vec& u, SpMat* j) override {
    const double inv_h2 = 1.0 / (h_ * h_);
    if (j->rows() != n_ || j->nonZeros() != 3 * n_ - 2) {
      std::vector<Triplet> entries;
      for (int i = 0; i < n_; ++i) {
        if (i > 0) entries.emplace_back(i, i - 1, 1.0);
        entries.emplace_back(i, i, 1.0);
        if (i + 1 < n_) entries.emplace_back(i, i + 1, 1.0);
      }
      j->resize(n_, n_);
      j->setFromTriplets(entries.begin(), entries.end());
    }
    for (int col = 0; col < n_; ++col) {
      for (SpMat::InnerIterator it(*j, col); it; ++it) {
        it.valueRef() = it.row() == col ? 2.0 * inv_h2 - lambda_ * std::exp(u[col]) : -inv_h2;
      }
    }
  }
  const Vec& solution() const { return solution_; }

 private:
  int n_;
  double lambda_;
  double h_ = 0.0;
  Vec solution_, r_;
};

// F = (x1 + x2 - 1, 2 x1 + 2 x2 - 3): an inconsistent linear system with a singular Jacobian.
class SingularSystem : public EquationSystem {
 public:
  int size() const override { return 2; }
  bool Residual(const Vec& x, Vec* f) override {
    f->resize(2);
    (*f)[0] = x[0] + x[1] - 1.0;
    (*f)[1] = 2.0 * x[0] + 2.0 * x[1] - 3.0;
    return true;
  }
  void Jacobian(const Vec&, SpMat* j) override {
    const std::vector<Triplet> entries = {{0, 0, 1.0}, {0, 1, 1.0}, {1, 0, 2.0}, {1, 1, 2.0}};
    j->resize(2, 2);
    j->setFromTriplets(entries.begin(), entries.end());
  }
};

// F_i = log(x_i) - c_i: undefined for x_i <= 0, where full steps from x0 = 10 land.
class LogSystem : public EquationSystem {
 public:
  int size() const override { return 3; }
  bool Residual(const Vec& x, Vec* f) override {
    if ((x.array() <= 0.0).any()) return false;
    *f = x.array().log() - c_.array();
    return true;
  }
  void Jacobian(const Vec& x, SpMat* j) override {
    std::vector<Triplet> entries;
    for (int i = 0; i < 3; ++i) entries.emplace_back(i, i, 1.0 / x[i]);
    j->resize(3, 3);
    j->setFromTriplets(entries.begin(), entries.end());
  }
  Vec Solution() const { return c_.array().exp(); }

 private:
  Vec c_{{0.0, 1.0, -1.0}};
};

// F cannot be evaluated anywhere.
class UnevaluableSystem : public EquationSystem {
 public:
  int size() const override { return 2; }
  bool Residual(const Vec&, Vec*) override { return false; }
  void Jacobian(const Vec&, SpMat* j) override { *j = SpMat(2, 2); }
};

// Counts the calls the solver makes, to check the summary's counts.
class CountingSystem : public EquationSystem {
 public:
  explicit CountingSystem(EquationSystem* inner) : inner_(inner) {}
  int size() const override { return inner_->size(); }
  bool Residual(const Vec& x, Vec* f) override {
    ++residual_calls;
    return inner_->Residual(x, f);
  }
  void Jacobian(const Vec& x, SpMat* j) override {
    ++jacobian_calls;
    inner_->Jacobian(x, j);
  }
  int residual_calls = 0;
  int jacobian_calls = 0;

 private:
  EquationSystem* inner_;
};

// Records what the callback sees.
struct History {
  std::vector<int> iterations;
  std::vector<double> residual_inf;
  std::vector<double> merit;
  std::vector<Vec> x;
  IterationCallback Callback() {
    return [this](const IterationInfo& info) {
      iterations.push_back(info.iteration);
      residual_inf.push_back(info.residual_inf);
      merit.push_back(info.merit);
      x.push_back(*info.x);
      return true;
    };
  }
};

// The summary agrees with a fresh evaluation at the returned point and with the counted calls.
void ExpectConsistentSummary(EquationSystem& system, const CountingSystem& counted, const Vec& x,
                             const SolverSummary& summary) {
  Vec f(system.size());
  ASSERT_TRUE(system.Residual(x, &f));
  EXPECT_EQ(summary.final_residual_inf, InfNorm(f));
  EXPECT_EQ(summary.final_merit, 0.5 * f.squaredNorm());
  EXPECT_EQ(summary.residual_evals, counted.residual_calls);
  EXPECT_EQ(summary.jacobian_evals, counted.jacobian_calls);
  EXPECT_GE(summary.residual_evals, summary.iterations + 1);
}

std::string Readable(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

std::string ParamName(const ::testing::TestParamInfo<std::string>& info) {
  return Readable(info.param);
}

// ----------------------------------------------------------------------------------------------
// Linear solvers.

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

TEST(CondensedCholeskyTest, WholeCondensedMatrixPathMatchesTheFullLu) {
  // Many contact dofs (400 of 1200): Kc factorised whole by CHOLMOD.
  ExpectCondensedMatchesLu(1200, 200, 5, false);
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

// ----------------------------------------------------------------------------------------------
// Options and the factory.

TEST(SolverOptionsTest, DefaultsAreValid) {
  std::string why = "untouched";
  EXPECT_TRUE(SolverOptions().IsValid(&why));
  EXPECT_TRUE(SolverOptions().IsValid(nullptr));
}

TEST(SolverOptionsTest, EachInvalidFieldIsRejectedByName) {
  struct Case {
    std::string field;
    std::function<void(SolverOptions*)> spoil;
  };
  const std::vector<Case> cases = {
      {"residual_tol", [](SolverOptions* o) { o->residual_tol = 0.0; }},
      {"residual_tol", [](SolverOptions* o) { o->residual_tol = std::nan(""); }},
      {"max_iterations", [](SolverOptions* o) { o->max_iterations = 0; }},
      {"step_tol", [](SolverOptions* o) { o->step_tol = -1.0; }},
      {"armijo", [](SolverOptions* o) { o->armijo = 0.0; }},
      {"armijo", [](SolverOptions* o) { o->armijo = 0.5; }},
      {"max_backtracks", [](SolverOptions* o) { o->max_backtracks = 0; }},
      {"backtrack_min", [](SolverOptions* o) { o->backtrack_min = 0.0; }},
      {"backtrack_max", [](SolverOptions* o) { o->backtrack_max = 1.0; }},
      {"backtrack_min", [](SolverOptions* o) { o->backtrack_min = 0.6; }},
      {"initial_radius_factor", [](SolverOptions* o) { o->initial_radius_factor = 0.0; }},
      {"accept_ratio", [](SolverOptions* o) { o->accept_ratio = 0.3; }},
      {"accept_ratio", [](SolverOptions* o) { o->accept_ratio = -0.1; }},
      {"max_updates", [](SolverOptions* o) { o->max_updates = 0; }},
      {"linear_solver", [](SolverOptions* o) { o->linear_solver = "gauss"; }},
  };
  for (const Case& c : cases) {
    SolverOptions options;
    c.spoil(&options);
    std::string why;
    EXPECT_FALSE(options.IsValid(&why)) << c.field;
    EXPECT_NE(why.find(c.field), std::string::npos) << "why: " << why;
    try {
      MakeEquationSolver("newton", options);
      ADD_FAILURE() << "no exception for " << c.field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(c.field), std::string::npos) << e.what();
    }
  }
}

TEST(EquationSolverFactoryTest, NamesAndUnknownNameListsValidOnes) {
  EXPECT_EQ(EquationSolverNames(), (std::vector<std::string>{"newton", "dogleg", "quasi-newton"}));
  for (const std::string& name : EquationSolverNames()) {
    EXPECT_EQ(MakeEquationSolver(name, SolverOptions())->name(), name);
  }
  try {
    MakeEquationSolver("levenberg", SolverOptions());
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    for (const std::string& name : EquationSolverNames()) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

// ----------------------------------------------------------------------------------------------
// Equation solvers, the same problems for each.

class EquationSolverTest : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<EquationSolver> Make(const SolverOptions& options = {}) {
    return MakeEquationSolver(GetParam(), options);
  }
  bool Is(const std::string& name) const { return GetParam() == name; }
};

TEST_P(EquationSolverTest, LinearSystem) {
  LinearTestSystem system(50);
  CountingSystem counted(&system);
  Vec x = Vec::Zero(50);
  History history;
  const SolverSummary summary = Make()->Solve(counted, &x, history.Callback());
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  EXPECT_LE(InfNorm(x - system.solution()), 1e-8);
  // The exact Newton step solves a linear system at once; quasi-Newton's first step is one.
  if (!Is("dogleg")) {
    EXPECT_EQ(summary.iterations, 1);
  }
  EXPECT_EQ(static_cast<int>(history.iterations.size()), summary.iterations);
  ExpectConsistentSummary(system, counted, x, summary);
}

TEST_P(EquationSolverTest, Rosenbrock) {
  RosenbrockSystem system;
  CountingSystem counted(&system);
  Vec x = RosenbrockSystem::Start();
  History history;
  const SolverSummary summary = Make()->Solve(counted, &x, history.Callback());
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  EXPECT_LE(InfNorm(x - RosenbrockSystem::Solution()), 1e-8);
  EXPECT_LE(summary.final_residual_inf, SolverOptions().residual_tol);
  EXPECT_DOUBLE_EQ(summary.initial_merit, 0.5 * (4.4 * 4.4 + 2.2 * 2.2));
  ExpectConsistentSummary(system, counted, x, summary);
  // One callback per iteration, numbered 1, 2, ...; the last one sees the returned point.
  ASSERT_EQ(static_cast<int>(history.iterations.size()), summary.iterations);
  for (int k = 0; k < summary.iterations; ++k) EXPECT_EQ(history.iterations[k], k + 1);
  EXPECT_EQ(history.x.back(), x);
  EXPECT_EQ(history.residual_inf.back(), summary.final_residual_inf);
}

TEST_P(EquationSolverTest, PowellBadlyScaled) {
  PowellBadlyScaledSystem system;
  CountingSystem counted(&system);
  Vec x = PowellBadlyScaledSystem::Start();
  SolverOptions options;
  // ||J^{-1}|| ~ 1e4 here: the residual must be near rounding for x to be accurate to 1e-8.
  options.residual_tol = 1e-13;
  const SolverSummary summary = Make(options)->Solve(counted, &x);
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  const Vec solution = PowellBadlyScaledSystem::Solution();
  EXPECT_NEAR(x[0] / solution[0], 1.0, 1e-8);
  EXPECT_NEAR(x[1] / solution[1], 1.0, 1e-8);
  ExpectConsistentSummary(system, counted, x, summary);
}

TEST_P(EquationSolverTest, Bratu1000) {
  BratuSystem system(1000, 1.0);
  CountingSystem counted(&system);
  Vec x = Vec::Zero(1000);
  SolverOptions options;
  // F carries 1/h^2 ~ 1e6: its rounding floor is ~1e-10.
  options.residual_tol = 1e-8;
  const SolverSummary summary = Make(options)->Solve(counted, &x);
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  EXPECT_LE(InfNorm(x - system.solution()), 1e-8);
  EXPECT_LE(summary.iterations, 30);
  ExpectConsistentSummary(system, counted, x, summary);
}

TEST_P(EquationSolverTest, UndefinedTrialPointsAreRejected) {
  LogSystem system;
  CountingSystem counted(&system);
  Vec x = Vec::Constant(3, 10.0);  // the full Newton step leaves the domain x > 0
  const SolverSummary summary = Make()->Solve(counted, &x);
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  EXPECT_LE(InfNorm(x - system.Solution()), 1e-8);
  ExpectConsistentSummary(system, counted, x, summary);
}

TEST_P(EquationSolverTest, CallbackCanStopTheSolve) {
  RosenbrockSystem system;
  Vec x = RosenbrockSystem::Start();
  int calls = 0;
  const SolverSummary summary = Make()->Solve(system, &x, [&](const IterationInfo& info) {
    ++calls;
    EXPECT_EQ(info.iteration, calls);
    return false;
  });
  EXPECT_EQ(summary.status, Status::kStoppedByCaller) << summary.message;
  EXPECT_EQ(summary.iterations, 1);
  EXPECT_EQ(calls, 1);
}

TEST_P(EquationSolverTest, MaxIterationsGivesLimitReachedAtTheLastIterate) {
  RosenbrockSystem system;
  CountingSystem counted(&system);
  Vec x = RosenbrockSystem::Start();
  SolverOptions options;
  options.max_iterations = 1;
  History history;
  const SolverSummary summary = Make(options)->Solve(counted, &x, history.Callback());
  EXPECT_EQ(summary.status, Status::kLimitReached) << summary.message;
  EXPECT_EQ(summary.iterations, 1);
  ASSERT_EQ(history.x.size(), 1u);
  EXPECT_EQ(history.x.back(), x);
  EXPECT_LE(summary.final_merit, summary.initial_merit);
  ExpectConsistentSummary(system, counted, x, summary);
}

TEST_P(EquationSolverTest, SingularSystemFailsWithMessage) {
  SingularSystem system;
  Vec x = Vec::Zero(2);
  SolverSummary summary;
  EXPECT_NO_THROW(summary = Make()->Solve(system, &x));
  EXPECT_EQ(summary.status, Status::kFailed);
  EXPECT_FALSE(summary.message.empty());
  // Dogleg does not stop at a singular Jacobian: it takes Cauchy steps to the least-squares
  // point and stops there (stagnation), naming the singular Jacobian.
  const std::string expected =
      Is("dogleg") ? "singular Jacobian" : "singular Jacobian at iteration 1";
  EXPECT_NE(summary.message.find(expected), std::string::npos) << summary.message;
  EXPECT_TRUE(x.allFinite());
}

TEST_P(EquationSolverTest, NonFiniteJacobianFails) {
  class NanJacobian : public RosenbrockSystem {
   public:
    void Jacobian(const Vec& x, SpMat* j) override {
      RosenbrockSystem::Jacobian(x, j);
      j->valuePtr()[0] = std::nan("");
    }
  } system;
  Vec x = RosenbrockSystem::Start();
  SolverSummary summary;
  EXPECT_NO_THROW(summary = Make()->Solve(system, &x));
  EXPECT_EQ(summary.status, Status::kFailed);
  EXPECT_NE(summary.message.find("non-finite Jacobian at iteration 1"), std::string::npos)
      << summary.message;
  EXPECT_EQ(x, RosenbrockSystem::Start());
}

TEST_P(EquationSolverTest, ResidualFailingAtTheStartFails) {
  UnevaluableSystem system;
  Vec x = Vec::Zero(2);
  const SolverSummary summary = Make()->Solve(system, &x);
  EXPECT_EQ(summary.status, Status::kFailed);
  EXPECT_NE(summary.message.find("initial point"), std::string::npos) << summary.message;
  EXPECT_EQ(summary.residual_evals, 1);
  EXPECT_EQ(summary.jacobian_evals, 0);
  EXPECT_EQ(summary.iterations, 0);
}

TEST_P(EquationSolverTest, ConvergedInitialPointTakesNoIteration) {
  RosenbrockSystem system;
  Vec x = RosenbrockSystem::Solution();
  const SolverSummary summary = Make()->Solve(system, &x);
  EXPECT_EQ(summary.status, Status::kConverged);
  EXPECT_EQ(summary.iterations, 0);
  EXPECT_EQ(summary.jacobian_evals, 0);
  EXPECT_EQ(summary.final_merit, 0.0);
}

TEST_P(EquationSolverTest, WrongSizeInitialPointThrows) {
  RosenbrockSystem system;
  Vec x = Vec::Zero(3);
  EXPECT_THROW(Make()->Solve(system, &x), std::invalid_argument);
  EXPECT_THROW(Make()->Solve(system, nullptr), std::invalid_argument);
}

TEST_P(EquationSolverTest, ReusableAcrossSolvesAndSizes) {
  SolverOptions options;
  options.residual_tol = 1e-8;
  auto solver = Make(options);
  BratuSystem bratu(300, 1.0);
  Vec first = Vec::Zero(300);
  const SolverSummary a = solver->Solve(bratu, &first);
  ASSERT_EQ(a.status, Status::kConverged) << a.message;

  RosenbrockSystem rosenbrock;  // another size and pattern in between
  Vec y = RosenbrockSystem::Start();
  ASSERT_EQ(solver->Solve(rosenbrock, &y).status, Status::kConverged);

  Vec second = Vec::Zero(300);
  const SolverSummary b = solver->Solve(bratu, &second);
  ASSERT_EQ(b.status, Status::kConverged) << b.message;
  EXPECT_EQ(first, second);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.residual_evals, b.residual_evals);
  EXPECT_EQ(a.jacobian_evals, b.jacobian_evals);
  EXPECT_EQ(a.linear_solves, b.linear_solves);
}

INSTANTIATE_TEST_SUITE_P(AllEquationSolvers, EquationSolverTest,
                         ::testing::ValuesIn(EquationSolverNames()), ParamName);

// Every equation solver with every linear solver on one nonlinear problem.
class EquationSolverWithLinearSolverTest
    : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(EquationSolverWithLinearSolverTest, Bratu) {
  SolverOptions options;
  options.linear_solver = std::get<1>(GetParam());
  options.residual_tol = 1e-8;
  BratuSystem system(500, 2.0);
  Vec x = Vec::Zero(500);
  const SolverSummary summary =
      MakeEquationSolver(std::get<0>(GetParam()), options)->Solve(system, &x);
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  EXPECT_LE(InfNorm(x - system.solution()), 1e-8);
}

INSTANTIATE_TEST_SUITE_P(
    AllPairs, EquationSolverWithLinearSolverTest,
    ::testing::Combine(::testing::ValuesIn(EquationSolverNames()),
                       ::testing::ValuesIn(LinearSolverNames())),
    [](const ::testing::TestParamInfo<std::tuple<std::string, std::string>>& info) {
      return Readable(std::get<0>(info.param) + "_with_" + std::get<1>(info.param));
    });

// ----------------------------------------------------------------------------------------------
// Method-specific properties.

TEST(NewtonSolverTest, OneJacobianAndFactorisationPerIteration) {
  RosenbrockSystem rosenbrock;
  Vec x = RosenbrockSystem::Start();
  const SolverSummary summary = MakeEquationSolver("newton", {})->Solve(rosenbrock, &x);
  ASSERT_EQ(summary.status, Status::kConverged);
  EXPECT_EQ(summary.jacobian_evals, summary.iterations);
  EXPECT_EQ(summary.linear_solves, summary.iterations);

  BratuSystem bratu(1000, 1.0);
  Vec u = Vec::Zero(1000);
  SolverOptions options;
  options.residual_tol = 1e-8;
  const SolverSummary b = MakeEquationSolver("newton", options)->Solve(bratu, &u);
  ASSERT_EQ(b.status, Status::kConverged);
  EXPECT_EQ(b.jacobian_evals, b.iterations);
  EXPECT_EQ(b.linear_solves, b.iterations);
  // Full steps throughout on this mildly nonlinear problem.
  EXPECT_EQ(b.residual_evals, b.iterations + 1);
}

TEST(NewtonSolverTest, ConvergesQuadratically) {
  BratuSystem system(1000, 3.0);  // closer to the turning point (3.51): more nonlinear
  Vec x = Vec::Zero(1000);
  SolverOptions options;
  options.residual_tol = 1e-9;
  History history;
  const SolverSummary summary =
      MakeEquationSolver("newton", options)->Solve(system, &x, history.Callback());
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  std::vector<double> errors = {InfNorm(system.solution())};  // e_0, from x0 = 0
  for (const Vec& xk : history.x) errors.push_back(InfNorm(xk - system.solution()));
  int checked = 0;
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    // Only where the error is in the asymptotic range and above the rounding floor.
    if (errors[k] > 0.1 || errors[k + 1] < 1e-11) continue;
    EXPECT_LE(errors[k + 1] / (errors[k] * errors[k]), 10.0)
        << "k=" << k << " e_k=" << errors[k] << " e_k+1=" << errors[k + 1];
    ++checked;
  }
  EXPECT_GE(checked, 2);
}

TEST(DoglegSolverTest, OneFactorisationPerAcceptedStep) {
  PowellBadlyScaledSystem system;
  Vec x = PowellBadlyScaledSystem::Start();
  History history;
  const SolverSummary summary =
      MakeEquationSolver("dogleg", {})->Solve(system, &x, history.Callback());
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  EXPECT_EQ(summary.jacobian_evals, summary.linear_solves);
  // Accepted trials are those that lowered the merit; each but the last is followed by one
  // Jacobian evaluation, and the first Jacobian is at x0.
  int accepted = 0;
  double previous = summary.initial_merit;
  for (double m : history.merit) {
    if (m != previous) ++accepted;
    previous = m;
  }
  EXPECT_EQ(summary.jacobian_evals, accepted);
  EXPECT_LE(summary.jacobian_evals, summary.iterations);
  EXPECT_EQ(summary.residual_evals, summary.iterations + 1);
}

TEST(QuasiNewtonSolverTest, UsesFewerJacobiansThanIterations) {
  BratuSystem system(1000, 1.0);
  Vec x = Vec::Zero(1000);
  SolverOptions options;
  options.residual_tol = 1e-8;
  const SolverSummary summary = MakeEquationSolver("quasi-newton", options)->Solve(system, &x);
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  EXPECT_EQ(summary.jacobian_evals, summary.linear_solves);
  EXPECT_LT(summary.jacobian_evals, summary.iterations);
}

TEST(QuasiNewtonSolverTest, RefreshesAfterMaxUpdates) {
  BratuSystem system(200, 3.0);
  Vec x = Vec::Zero(200);
  SolverOptions options;
  options.residual_tol = 1e-8;
  options.max_updates = 1;
  const SolverSummary summary = MakeEquationSolver("quasi-newton", options)->Solve(system, &x);
  ASSERT_EQ(summary.status, Status::kConverged) << summary.message;
  // At most one update between two factorisations: two iterations per Jacobian at most.
  EXPECT_GE(2 * summary.jacobian_evals, summary.iterations);
  EXPECT_LE(InfNorm(x - system.solution()), 1e-8);
}

}  // namespace
}  // namespace cb
