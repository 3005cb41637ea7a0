// Tests of src/solvers/equation_solver: the options, the factory, and every equation solver
// (Newton, dogleg, quasi-Newton) on the same small systems with known solutions, with every
// linear solver.
#include "solvers/equation_solver.h"

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/types.h"
#include "solver_test_support.h"
#include "solvers/equation_system.h"
#include "solvers/linear_solver.h"

namespace cb {
namespace {

using ::cb::fixtures::BratuSystem;
using ::cb::fixtures::History;
using ::cb::fixtures::InfNorm;
using ::cb::fixtures::ParamName;
using ::cb::fixtures::PowellBadlyScaledSystem;
using ::cb::fixtures::Readable;
using ::cb::fixtures::RosenbrockSystem;

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
      {"nonmonotone_window", [](SolverOptions* o) { o->nonmonotone_window = 0; }},
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

}  // namespace
}  // namespace cb
