// Tests of src/solvers/newton: what sets Newton's method apart from the other equation solvers
// (one Jacobian and factorisation per iteration, quadratic convergence).
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "core/types.h"
#include "solver_test_support.h"
#include "solvers/equation_solver.h"

namespace cb {
namespace {

using ::cb::fixtures::BratuSystem;
using ::cb::fixtures::History;
using ::cb::fixtures::InfNorm;
using ::cb::fixtures::RosenbrockSystem;

// Bratu whose residual and Jacobian come from one pass, counting the passes of each kind.
class OnePassBratu final : public BratuSystem {
 public:
  using BratuSystem::BratuSystem;
  bool Residual(const Vec& u, Vec* f) override {
    ++residuals;
    return BratuSystem::Residual(u, f);
  }
  void Jacobian(const Vec& u, SpMat* j) override {
    ++jacobians;
    BratuSystem::Jacobian(u, j);
  }
  bool ResidualAndJacobian(const Vec& u, Vec* f, SpMat* j) override {
    ++both;
    BratuSystem::Jacobian(u, j);
    return BratuSystem::Residual(u, f);
  }
  bool shares_residual_and_jacobian() const override { return true; }
  int residuals = 0, jacobians = 0, both = 0;
};

TEST(NewtonSolverTest, OneJacobianAndFactorisationPerIteration) {
  RosenbrockSystem rosenbrock;
  Vec x = RosenbrockSystem::Start();
  const SolverSummary summary = MakeEquationSolver("newton", {})->Solve(rosenbrock, &x);
  ASSERT_EQ(summary.status, Status::kConverged);
  EXPECT_EQ(summary.jacobian_evals, summary.iterations);
  EXPECT_EQ(summary.linear_solves, summary.iterations);

  OnePassBratu bratu(1000, 1.0);
  Vec u = Vec::Zero(1000);
  SolverOptions options;
  options.residual_tol = 1e-8;
  const SolverSummary b = MakeEquationSolver("newton", options)->Solve(bratu, &u);
  ASSERT_EQ(b.status, Status::kConverged);
  EXPECT_EQ(b.jacobian_evals, b.iterations);
  EXPECT_EQ(b.linear_solves, b.iterations);
  // Full steps throughout on this mildly nonlinear problem, so every Jacobian came from the pass
  // that evaluated the residual at the same point (the start, then each accepted step).
  EXPECT_EQ(b.residual_evals, b.iterations + 1);
  EXPECT_EQ(bratu.both, b.iterations + 1);
  EXPECT_EQ(bratu.jacobians, 0);
  EXPECT_EQ(bratu.residuals, 0);
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

}  // namespace
}  // namespace cb
