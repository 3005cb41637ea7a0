// Tests of src/solvers/dogleg: what sets the trust-region dogleg apart from the other equation
// solvers (a new Jacobian and factorisation only after an accepted step).
#include <gtest/gtest.h>

#include "core/types.h"
#include "solver_test_support.h"
#include "solvers/equation_solver.h"

namespace cb {
namespace {

using ::cb::fixtures::History;
using ::cb::fixtures::PowellBadlyScaledSystem;

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

}  // namespace
}  // namespace cb
