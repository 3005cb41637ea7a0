// KinkLocator (path/kink_location.h) between two states of the bar pushed against a wall: the
// bar touches the wall at lambda_c (tests/bar_wall.h), where g = r = 0.
#include "path/kink_location.h"

#include <gtest/gtest.h>

#include <vector>

#include "bar_wall.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "problems/problem.h"

namespace cb {
namespace {

class KinkCollector final : public PathObserver {
 public:
  void OnKink(const KinkRecord& k) override { kinks.push_back(k); }
  std::vector<KinkRecord> kinks;
};

class KinkLocationTest : public ::testing::Test {
 protected:
  KinkLocationTest() : p_(MakeProblem("bar-wall")), bar_(p_) {}

  State StateAt(double lambda) const { return bar_.StateAt(lambda); }

  KinksOfStep Locate(const State& a, const State& b, KinkCollector* c) {
    return KinkLocator(*p_.model, p_.scales, f_, options_).Locate(7, a, b, *c);
  }

  Problem p_;
  fixtures::BarWallClosedForm bar_;
  ImplicitFb f_;
  PathOptions options_;
};

TEST_F(KinkLocationTest, AStepOntoTheWallHasItsKinkWhereTheBarTouches) {
  KinkCollector c;
  const KinksOfStep kinks = Locate(StateAt(0.8 * bar_.lambda_c), StateAt(1.3 * bar_.lambda_c), &c);
  EXPECT_EQ(kinks.found, 1);
  ASSERT_EQ(c.kinks.size(), 1u);
  const KinkRecord& k = c.kinks[0];
  EXPECT_EQ(k.step, 7);
  EXPECT_EQ(k.pair, 0);
  EXPECT_TRUE(k.verdict.verified);
  EXPECT_TRUE(k.between);
  EXPECT_NEAR(k.state.lambda, bar_.lambda_c, 1e-8 * bar_.lambda_c);
  EXPECT_NEAR(k.state.u[p_.control_dof], bar_.gap, 1e-10);
  EXPECT_NEAR(k.state.r[0], 0.0, 1e-8);
  ASSERT_TRUE(kinks.nearest.has_value());
  EXPECT_EQ(kinks.nearest->lambda, k.state.lambda);
}

// The kink does not depend on the direction the path crosses it in (unloading off the wall).
TEST_F(KinkLocationTest, AStepOffTheWallHasTheSameKink) {
  KinkCollector c;
  const KinksOfStep kinks = Locate(StateAt(1.3 * bar_.lambda_c), StateAt(0.8 * bar_.lambda_c), &c);
  EXPECT_EQ(kinks.found, 1);
  ASSERT_EQ(c.kinks.size(), 1u);
  EXPECT_NEAR(c.kinks[0].state.lambda, bar_.lambda_c, 1e-8 * bar_.lambda_c);
}

TEST_F(KinkLocationTest, AStepThatKeepsItsContactStatusHasNoKink) {
  KinkCollector c;
  EXPECT_EQ(Locate(StateAt(0.2 * bar_.lambda_c), StateAt(0.8 * bar_.lambda_c), &c).found, 0);
  EXPECT_EQ(Locate(StateAt(1.2 * bar_.lambda_c), StateAt(1.8 * bar_.lambda_c), &c).found, 0);
  EXPECT_TRUE(c.kinks.empty());
}

}  // namespace
}  // namespace cb
