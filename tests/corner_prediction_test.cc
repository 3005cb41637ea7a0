// CornerPrediction (path/corner_prediction.h) on the bar pushed against a wall, whose path is
// two straight pieces meeting at the kink lambda_c (tests/bar_wall.h): a prediction bent at the
// contact change lies on the path's other piece, at the prediction's length along the path.
#include "path/corner_prediction.h"

#include <gtest/gtest.h>

#include <optional>

#include "bar_wall.h"
#include "formulations/common/start_solvers.h"
#include "problems/problem.h"

namespace cb {
namespace {

class CornerPredictionTest : public ::testing::Test {
 protected:
  CornerPredictionTest() : p_(MakeProblem("bar-wall")), bar_(p_) {}

  // The straight prediction from the state at lambda `at`, reached from `before`: the secant
  // of the last step continued for `ahead` in load.
  Increment Straight(double before, double at, double ahead) const {
    const State a = bar_.StateAt(before);
    const State b = bar_.StateAt(at);
    const double scale = ahead / (at - before);
    return {(b.u - a.u) * scale, ahead};
  }
  std::optional<Increment> Bent(double before, double at, double ahead) const {
    return CornerPrediction(*p_.model, p_.scales, bar_.StateAt(before), bar_.StateAt(at),
                            Straight(before, at, ahead), w_);
  }
  double Length(const State& a, const State& b) const {
    return HNorm(b.u - a.u, b.lambda - a.lambda, w_);
  }

  Problem p_;
  fixtures::BarWallClosedForm bar_;
  double w_ = PathOptions().lambda_weight;
};

TEST_F(CornerPredictionTest, APredictionIntoTheWallIsBentOntoTheContactPiece) {
  const double lc = bar_.lambda_c;
  const Increment straight = Straight(0.5 * lc, 0.8 * lc, 0.5 * lc);
  const State at = bar_.StateAt(0.8 * lc);
  ASSERT_GT(at.u[p_.control_dof] + straight.du[p_.control_dof], bar_.gap);  // into the wall
  const std::optional<Increment> bent = Bent(0.5 * lc, 0.8 * lc, 0.5 * lc);
  ASSERT_TRUE(bent.has_value());
  // On the contact piece: u = gap, above lambda_c.
  State end = at;
  end.u = at.u + bent->du;
  end.lambda = at.lambda + bent->dlambda;
  EXPECT_NEAR(end.u[p_.control_dof], bar_.gap, 1e-12 * bar_.gap);
  EXPECT_GT(end.lambda, lc);
  // As far along the path as the straight prediction is long.
  const State corner = bar_.StateAt(lc);
  const double theta = HNorm(straight.du, straight.dlambda, w_);
  EXPECT_NEAR(Length(at, corner) + Length(corner, end), theta, 1e-12 * theta);
}

// Unloading off the wall: the prediction along the contact piece is bent onto the free one.
TEST_F(CornerPredictionTest, APredictionOffTheWallIsBentOntoTheFreePiece) {
  const double lc = bar_.lambda_c;
  const std::optional<Increment> bent = Bent(1.6 * lc, 1.3 * lc, -0.6 * lc);
  ASSERT_TRUE(bent.has_value());
  const State at = bar_.StateAt(1.3 * lc);
  const double lambda = at.lambda + bent->dlambda;
  EXPECT_LT(lambda, lc);
  EXPECT_NEAR(at.u[p_.control_dof] + bent->du[p_.control_dof],
              bar_.StateAt(lambda).u[p_.control_dof], 1e-12 * bar_.gap);
}

TEST_F(CornerPredictionTest, APredictionThatKeepsTheContactStatusIsNotBent) {
  const double lc = bar_.lambda_c;
  EXPECT_FALSE(Bent(0.2 * lc, 0.4 * lc, 0.2 * lc).has_value());  // stops short of the wall
  EXPECT_FALSE(Bent(1.2 * lc, 1.4 * lc, 0.3 * lc).has_value());  // on the wall, loading
}

// The solver a start gets (start_solvers.h): the nonmonotone search for the starts far from
// their answer, the monotone one for every other warm start.
TEST(StartSolversTest, ColdStartsAndStartsAcrossAContactChangeSearchNonmonotonically) {
  SolverOptions options;
  options.nonmonotone_window = 7;
  StartPoint warm;
  StartPoint across;
  across.across_contact_change = true;
  StartPoint cold;
  cold.kind = StartKind::kCold;
  EXPECT_EQ(SolverOptionsFor(warm, options).nonmonotone_window, 1);
  EXPECT_EQ(SolverOptionsFor(across, options).nonmonotone_window, 7);
  EXPECT_EQ(SolverOptionsFor(cold, options).nonmonotone_window, 7);
}

}  // namespace
}  // namespace cb
