// SolveAndJudge (path/step_solve.h) against the bar pushed against a wall, whose path is known
// in closed form (tests/bar_wall.h).
#include "path/step_solve.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bar_wall.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "problems/problem.h"

namespace cb {
namespace {

class StepSolveTest : public ::testing::Test {
 protected:
  StepSolveTest() : p_(MakeProblem("bar-wall")), bar_(p_) {}

  JudgedStep Solve(Formulation& f, const State& base, const StepConstraint& constraint) const {
    StartPoint start;
    start.du = Vec::Zero(p_.model->num_dofs());
    start.r = base.r;
    PathOptions options;
    return SolveAndJudge(f, StepProblem{p_.model.get(), base, constraint, p_.scales}, start,
                         options);
  }

  Problem p_;
  fixtures::BarWallClosedForm bar_;
};

TEST_F(StepSolveTest, AFixedLoadStepPastContactReachesTheClosedFormFromItsBase) {
  ImplicitFb f;
  const State base = bar_.StateAt(0.5 * bar_.lambda_c);
  const double lambda = 1.5 * bar_.lambda_c;
  const JudgedStep s = Solve(f, base, StepConstraint::FixedLoad(lambda));
  ASSERT_TRUE(s.verdict.verified) << s.result.message;
  // The state is the base plus the increment, not the increment alone.
  EXPECT_EQ(s.state.u, Vec(base.u + s.result.point.du));
  EXPECT_EQ(s.state.lambda, base.lambda + s.result.point.dlambda);
  EXPECT_EQ(s.state.r, s.result.point.r);
  EXPECT_NEAR(s.state.lambda, lambda, 1e-12 * lambda);
  EXPECT_NEAR(s.state.u[p_.control_dof], bar_.gap, 1e-10);
  EXPECT_NEAR(s.state.r[0], -(lambda - bar_.lambda_c), 1e-8);
  EXPECT_EQ(s.n_contact, 1);  // the bar is on the wall
}

TEST_F(StepSolveTest, AStepThatStaysOffTheWallCountsNoContact) {
  ImplicitFb f;
  const State base = bar_.StateAt(0.25 * bar_.lambda_c);
  const double lambda = 0.75 * bar_.lambda_c;
  const JudgedStep s = Solve(f, base, StepConstraint::FixedLoad(lambda));
  ASSERT_TRUE(s.verdict.verified) << s.result.message;
  EXPECT_NEAR(s.state.u[p_.control_dof], lambda * bar_.length / bar_.ea, 1e-10);
  EXPECT_EQ(s.n_contact, 0);
}

// An arc-length step (33) ends at H-distance theta from its base.
TEST_F(StepSolveTest, AnArcLengthStepEndsAtDistanceThetaFromItsBase) {
  ImplicitFb f;
  const State base = bar_.StateAt(0.5 * bar_.lambda_c);
  const double theta = 0.1 * bar_.lambda_c;
  const JudgedStep s = Solve(f, base, StepConstraint::ArcLength(theta));
  ASSERT_TRUE(s.verdict.verified) << s.result.message;
  const double distance =
      std::sqrt((s.state.u - base.u).squaredNorm() +
                (s.state.lambda - base.lambda) * (s.state.lambda - base.lambda));
  EXPECT_NEAR(distance, theta, 1e-9 * theta);
}

// A solve that cannot converge is judged, not trusted: its own status does not make it verified.
TEST_F(StepSolveTest, AnUnconvergedSolveIsNotVerified) {
  ImplicitFbOptions o;
  o.solver_options.max_iterations = 1;
  ImplicitFb f(o);
  const JudgedStep s =
      Solve(f, ZeroState(*p_.model), StepConstraint::FixedLoad(3.0 * bar_.lambda_c));
  EXPECT_FALSE(s.verdict.verified);
  EXPECT_GT(s.verdict.eq_res + s.verdict.comp_res + s.verdict.step_res, 1e-8);
}

}  // namespace
}  // namespace cb
