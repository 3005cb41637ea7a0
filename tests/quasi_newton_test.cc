// Tests of src/solvers/quasi_newton: what sets the quasi-Newton method apart from the other
// equation solvers (fewer Jacobians than iterations, a refresh after max_updates updates).
#include <gtest/gtest.h>

#include "core/types.h"
#include "solver_test_support.h"
#include "solvers/equation_solver.h"

namespace cb {
namespace {

using ::cb::fixtures::BratuSystem;
using ::cb::fixtures::InfNorm;

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
