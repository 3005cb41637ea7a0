// The two ways an arc-length step leaves its origin (path/step_leg.h), on 2-dof increments.
#include "path/step_leg.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cb {
namespace {

Vec Vec2(double a, double b) {
  Vec v(2);
  v << a, b;
  return v;
}

StepPoint Answer(const Vec& du, double dlambda) {
  StepPoint p;
  p.du = du;
  p.dlambda = dlambda;
  return p;
}

StepOrigin Origin() {
  StepOrigin o;
  o.state = {Vec2(1.0, 2.0), Vec::Zero(1), 3.0};
  o.unstable_modes = 0;
  o.previous = StepOrigin::PreviousStep{0.5, 0, std::nullopt};
  return o;
}

TEST(StepLegTest, AlongTheBranchThePredictionIsTheHeadingScaledToTheArcLength) {
  const double w = 2.0;
  const Increment heading{Vec2(3.0, 4.0), 1.0};
  const ContinuationLeg leg(Origin(), 2, heading, {{-heading.du, -heading.dlambda}}, w);
  EXPECT_FALSE(leg.switches_branch());
  EXPECT_EQ(leg.branch(), 2);
  EXPECT_EQ(leg.predictions_per_arc_length(), 1);
  EXPECT_EQ(leg.origin().state.lambda, 3.0);
  EXPECT_EQ(leg.origin().unstable_modes, 0);
  for (const double theta : {0.1, 0.05}) {
    const Increment p = leg.Predict(0, theta);
    // On the arc (33) of radius theta, in the heading's direction.
    EXPECT_NEAR(HNorm(p.du, p.dlambda, w), theta, 1e-15);
    const double s = p.dlambda / heading.dlambda;
    EXPECT_GT(s, 0.0);
    EXPECT_NEAR((p.du - s * heading.du).norm(), 0.0, 1e-15);
  }
}

TEST(StepLegTest, AlongTheBranchTheOtherRootIsReversed) {
  const Increment heading{Vec2(0.6, 0.0), 0.8};
  const ContinuationLeg leg(Origin(), 0, heading, {{-heading.du, -heading.dlambda}}, 1.0);
  EXPECT_TRUE(leg.Reversed(Answer(-heading.du, -heading.dlambda), 1.0));
  EXPECT_FALSE(leg.Reversed(Answer(heading.du, heading.dlambda), 1.0));
}

// Off a bifurcation point: at constant load along the null vector, + then -, at each theta, each
// closed by the plane orthogonal to the mode in the same sense at distance theta.
TEST(StepLegTest, OffABifurcationPointBothSensesOfTheNullVectorAreTried) {
  CriticalPointRecord bifurcation;
  bifurcation.state = {Vec2(1.0, 2.0), Vec::Zero(1), 3.0};
  bifurcation.mode = Vec2(0.6, 0.8);
  const BranchSwitchLeg leg(bifurcation, 1);
  EXPECT_TRUE(leg.switches_branch());
  EXPECT_EQ(leg.branch(), 1);
  EXPECT_EQ(leg.predictions_per_arc_length(), 2);
  EXPECT_EQ(leg.origin().state.u, bifurcation.state.u);
  // No count at the bifurcation point, and no previous step on the new branch.
  EXPECT_EQ(leg.origin().unstable_modes, -1);
  EXPECT_FALSE(leg.origin().previous.has_value());
  const double theta = 0.2;
  const Increment plus = leg.Predict(0, theta);
  const Increment minus = leg.Predict(1, theta);
  EXPECT_EQ(plus.du, Vec(theta * bifurcation.mode));
  EXPECT_EQ(minus.du, Vec(-plus.du));
  EXPECT_EQ(plus.dlambda, 0.0);
  EXPECT_EQ(minus.dlambda, 0.0);
  EXPECT_EQ(leg.Predict(2, theta).du, plus.du);
  for (int attempt : {0, 1}) {
    const StepConstraint plane = leg.Constraint(attempt, theta, 1.0);
    EXPECT_EQ(plane.kind, ConstraintKind::kHyperplane);
    EXPECT_EQ(plane.arc_length, theta);
    EXPECT_EQ(plane.normal_lambda, 0.0);
    // The prediction lies on its own plane.
    const Increment predicted = leg.Predict(attempt, theta);
    EXPECT_NEAR(plane.normal.dot(predicted.du) / theta - 1.0, 0.0, 1e-15);
  }
}

}  // namespace
}  // namespace cb
