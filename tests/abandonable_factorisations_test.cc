// Every long factorisation inside the library that a SIGINT/SIGTERM could only wait for runs on a
// worker an interrupt abandons (core/abandonable_work.h; issue 30): the condensed Cholesky's
// contact block (CHOLMOD's factor of A + D0 and the dense factor of M), CHOLMOD's and KLU's
// symbolic analyses, KLU's refactorisation, and the bordered stiffness of the arc-length
// tangent. Each test arms an interrupt for one worker by its thread name: a start hook holds that
// worker until the interrupt poll has answered true, so the abandonment is certain without a
// problem slow to factorise. Before the change there was no such worker: the factorisation ran
// to its end on the calling thread and succeeded, and every test here failed.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/abandonable_work.h"
#include "core/interrupt_poll.h"
#include "core/types.h"
#include "path/path.h"
#include "path/stability.h"
#include "problems/problem.h"
#include "solvers/condensed_cholesky.h"
#include "solvers/dense_cholesky.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {
namespace {

std::atomic<const char*> g_armed{nullptr};
std::atomic<bool> g_armed_started{false};
std::atomic<bool> g_released{false};

// Holds the armed worker until the interrupt is over (so that the poll has said "interrupted").
void HoldArmedWorker(const char* name) {
  const char* armed = g_armed.load();
  if (armed == nullptr || std::strcmp(name, armed) != 0) return;
  g_armed_started = true;
  while (!g_released.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

bool InterruptOnceArmedWorkerRuns() { return g_armed_started.load(); }

// An interrupt that arrives while the worker named `name` runs, for the life of this object.
class InterruptDuring {
 public:
  explicit InterruptDuring(const char* name) {
    g_armed_started = false;
    g_released = false;
    g_armed = name;
    SetWorkerStartHookForTesting(HoldArmedWorker);
    SetInterruptPoll(InterruptOnceArmedWorkerRuns);
  }
  ~InterruptDuring() {
    SetInterruptPoll(nullptr);
    SetWorkerStartHookForTesting(nullptr);
    g_released = true;  // lets a held worker go
    g_armed = nullptr;
  }
  InterruptDuring(const InterruptDuring&) = delete;
  InterruptDuring& operator=(const InterruptDuring&) = delete;
  bool worker_ran() const { return g_armed_started.load(); }
};

bool SaysAbandoned(const std::string& message) {
  return message.find("abandoned on an interrupt") != std::string::npos;
}

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
// A Jacobian of the block form of JacobianStructure (as in condensed_cholesky_test.cc, smaller
// in what it varies): A a banded SPD chain, `nc` pairs on distinct dofs (G, H = -coupling G^T,
// E = I, Da < 0 < Db), one border column and row (dlambda and its row).
SpMat BlockJacobian(int d, int nc, double coupling, double stiffness_scale) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  const int n = d + 2 * nc + 1, dl = d + 2 * nc;
  std::vector<Triplet> e;
  for (int j = 0; j < d; ++j) {
    e.emplace_back(j, j, stiffness_scale * (4.0 + u(rng)));
    for (int k = 1; k <= 2 && j + k < d; ++k) {
      const double v = -0.5 * stiffness_scale * u(rng);
      e.emplace_back(j + k, j, v);
      e.emplace_back(j, j + k, v);
    }
    if (j % 3 == 0) e.emplace_back(j, dl, -0.3 * u(rng));  // U1: the load column
  }
  for (int p = 0; p < nc; ++p) {
    const int dof = 2 * p * (d / (2 * nc));
    const double g0 = u(rng), g1 = u(rng) - 0.6;
    e.emplace_back(d + p, dof, g0);
    e.emplace_back(d + p, dof + 1, g1);
    e.emplace_back(dof, d + nc + p, -coupling * g0);
    e.emplace_back(dof + 1, d + nc + p, -coupling * g1);
    e.emplace_back(d + p, d + p, 1.0);
    e.emplace_back(d + nc + p, d + p, -u(rng));
    e.emplace_back(d + nc + p, d + nc + p, u(rng));
    e.emplace_back(dl, d + p, -0.01 * u(rng));
  }
  e.emplace_back(dl, dl, -1.0);
  SpMat a(n, n);
  a.setFromTriplets(e.begin(), e.end());
  a.makeCompressed();
  return a;
}

// 70 000 dofs (Kc's lower triangle over 200 000 entries: the large matrices the workers take)
// and 600 pairs on 1 200 contact dofs (few: the contact-block update; M of order >= 1 000).
constexpr int kDofs = 70000, kPairs = 600;
constexpr double kCoupling = 0.3;

// The "cholmod" solver abandons the factorisation the worker `name` does, says so, and starts no
// fall-back; once the interrupt is gone, the same solver factorises the matrix and solves it.
void ExpectTheCondensedSolverAbandons(const char* name) {
  const JacobianStructure structure{kDofs, kPairs, kCoupling};
  auto cholmod = MakeLinearSolver("cholmod");
  cholmod->SetStructure(&structure);
  const SpMat a = BlockJacobian(kDofs, kPairs, kCoupling, 1.0);
  {
    const InterruptDuring interrupt(name);
    EXPECT_FALSE(cholmod->Factorize(a));
    EXPECT_TRUE(interrupt.worker_ran()) << "no " << name << " worker";
    EXPECT_TRUE(SaysAbandoned(cholmod->message())) << cholmod->message();
    EXPECT_EQ(CondensedStats(*cholmod)->fallback_factorizations, 0);
  }
  ASSERT_TRUE(cholmod->Factorize(a)) << cholmod->message();
  const Vec b = Vec::LinSpaced(a.rows(), -1.0, 2.0);
  Vec x;
  ASSERT_TRUE(cholmod->Solve(b, &x)) << cholmod->message();
  EXPECT_LE((a * x - b).norm() / b.norm(), 1e-12);
  EXPECT_EQ(CondensedStats(*cholmod)->contact_block_factorizations, 1);
}

// P1's first iteration: CHOLMOD's factorisation of A + D0 for the contact-block update.
TEST(AbandonableFactorisationsTest, TheContactBlocksSparseFactorisation) {
  ExpectTheCondensedSolverAbandons("cholmod-factor");
}

// The dense factor of the contact block M, every iteration (order c: 9 075 on hertz-3d n = 54).
TEST(AbandonableFactorisationsTest, TheContactBlocksDenseFactorisation) {
  ExpectTheCondensedSolverAbandons(kInterruptibleDenseThreadName);
}

// CHOLMOD's symbolic analyses (the ordering of the interior, then Kc in that order).
TEST(AbandonableFactorisationsTest, CholmodsSymbolicAnalysis) {
  ExpectTheCondensedSolverAbandons("cholmod-analyse");
}

// A banded nonsymmetric matrix, 21 entries a column (over 200 000 for n = 12 000).
SpMat Banded(int n, double shift) {
  std::vector<Triplet> e;
  for (int j = 0; j < n; ++j) {
    for (int i = std::max(0, j - 10); i <= std::min(n - 1, j + 10); ++i) {
      e.emplace_back(i, j, i == j ? 30.0 + shift : -1.0 + 0.01 * (i - j));
    }
  }
  SpMat a(n, n);
  a.setFromTriplets(e.begin(), e.end());
  a.makeCompressed();
  return a;
}

// KLU's symbolic analysis, then its refactorisation in the last pivot order (as slow as a full
// factorisation on a 3-D fill: the fall-back's second and later Newton iterations).
TEST(AbandonableFactorisationsTest, KlusAnalysisAndRefactorisation) {
  auto klu = MakeLinearSolver("klu");
  const SpMat a = Banded(12000, 0.0), changed = Banded(12000, 1.0);
  {
    const InterruptDuring interrupt("klu-analyse");
    EXPECT_FALSE(klu->Factorize(a));
    EXPECT_TRUE(interrupt.worker_ran()) << "no klu-analyse worker";
    EXPECT_TRUE(SaysAbandoned(klu->message())) << klu->message();
  }
  ASSERT_TRUE(klu->Factorize(a)) << klu->message();
  const int full = klu->num_full_factorizations();
  {
    const InterruptDuring interrupt("klu-refactor");
    EXPECT_FALSE(klu->Factorize(changed));
    EXPECT_TRUE(interrupt.worker_ran()) << "no klu-refactor worker";
    EXPECT_TRUE(SaysAbandoned(klu->message())) << klu->message();
    EXPECT_EQ(klu->num_full_factorizations(), full);  // nothing else started
  }
  ASSERT_TRUE(klu->Factorize(changed)) << klu->message();  // analysed and factorised afresh
  const Vec b = Vec::LinSpaced(changed.rows(), -1.0, 2.0);
  Vec x;
  ASSERT_TRUE(klu->Solve(b, &x)) << klu->message();
  EXPECT_LE((changed * x - b).norm() / b.norm(), 1e-13);
}
#endif

// The dense Cholesky of a large block on its own: abandoned, it says so and keeps no factor.
TEST(AbandonableFactorisationsTest, ALargeDenseCholesky) {
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  const int n = kInterruptibleDenseMinOrder;
  DenseCholesky cholesky;
  const Mat spd = Mat::Identity(n, n) * static_cast<double>(n) + Mat::Constant(n, n, 0.5);
  cholesky.matrix() = spd;
  {
    const InterruptDuring interrupt(kInterruptibleDenseThreadName);
    EXPECT_FALSE(cholesky.Factorize());
    EXPECT_TRUE(interrupt.worker_ran());
    EXPECT_TRUE(cholesky.interrupted());
  }
  cholesky.matrix() = spd;
  ASSERT_TRUE(cholesky.Factorize());
  EXPECT_FALSE(cholesky.interrupted());
  Vec b = Vec::Ones(n);
  cholesky.SolveInPlace(b.data(), n, 1);
  EXPECT_LE((spd * b - Vec::Ones(n)).norm(), 1e-10 * std::sqrt(n));
#endif
}

// An abandoned worker is counted until it ends, so that the program ends without the static
// destructors meanwhile (core/abandonable_work.h: they tore down the BLAS under an abandoned
// CHOLMOD factorisation, and a SIGTERM run crashed at exit).
TEST(AbandonableFactorisationsTest, AnAbandonedWorkerIsCountedUntilItEnds) {
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  const int n = kInterruptibleDenseMinOrder;
  DenseCholesky cholesky;
  cholesky.matrix() = Mat::Identity(n, n);
  const auto none_running = [] {  // earlier tests' released workers may still be ending
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (AbandonedWorkRunning() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return !AbandonedWorkRunning();
  };
  ASSERT_TRUE(none_running());
  {
    const InterruptDuring interrupt(kInterruptibleDenseThreadName);
    EXPECT_FALSE(cholesky.Factorize());
    EXPECT_TRUE(AbandonedWorkRunning());  // held at its start
  }
  EXPECT_TRUE(none_running());
#endif
}

// The arc-length start's tangent predictor on a 3-D plate (the bordered stiffness over 200 000
// entries): abandoned, it fails saying so; without the interrupt it gives the tangent.
TEST(AbandonableFactorisationsTest, TheTangentPredictorsFactorisation) {
  const Problem plate = MakeProblem("plate-3d", {{"nx", "16"}, {"ny", "16"}, {"nz", "4"}});
  const State start = ZeroState(*plate.model);
  Vec du;
  double dlambda = 0.0;
  std::string why;
  {
    const InterruptDuring interrupt(kInterruptibleStiffnessThreadName);
    EXPECT_FALSE(
        TangentPredictor(*plate.model, plate.scales, start, 0.1, 1.0, &du, &dlambda, &why));
    EXPECT_TRUE(interrupt.worker_ran()) << "no " << kInterruptibleStiffnessThreadName << " worker";
    EXPECT_TRUE(SaysAbandoned(why)) << why;
  }
  ASSERT_TRUE(TangentPredictor(*plate.model, plate.scales, start, 0.1, 1.0, &du, &dlambda, &why))
      << why;
  EXPECT_GT(dlambda, 0.0);
  EXPECT_TRUE(du.allFinite());
}

}  // namespace
}  // namespace cb
