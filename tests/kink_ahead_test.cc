// KinkAheadFinder (path/kink_ahead.h) on the steep, soft two-bar truss coming down onto its
// floor, where the load is at its minimum (the closed form of tests/fixtures.h): from the last
// two states before the floor, the kink ahead is where the closed form puts it, and the path
// leaves it along the floor with the load rising.
#include "path/kink_ahead.h"

#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "fixtures.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "problems/problem.h"

namespace cb {
namespace {

struct AcceptedStates final : PathObserver {
  void OnAttempt(const StepAttempt& a) override {
    if (a.accepted) states.push_back(a.state);
  }
  void OnKink(const KinkRecord& k) override { kink_steps.push_back(k.step); }
  std::vector<State> states;
  std::vector<int> kink_steps;
};

TEST(KinkAheadTest, TheFloorAtTheLoadMinimumIsFoundAheadAndLeftAlongTheFloor) {
  const Problem p = MakeProblem(
      "two-bar-obstacle", {{"height", "1"}, {"floor_height", "0.4"}, {"axial_stiffness", "1"}});
  const fixtures::TwoBarClosedForm t = fixtures::TwoBarOf(p);
  const double floor = p.parameters.Real("floor_height");
  ImplicitFb f;
  PathOptions o;
  o.arc_length = 0.05;
  o.max_steps = 40;
  AcceptedStates path;
  ASSERT_EQ(TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), f, o, &path).status,
            Status::kConverged);
  ASSERT_EQ(path.kink_steps.size(), 1u);
  const int k = path.kink_steps[0];  // the floor is met within step k
  ASSERT_GE(k, 3);
  const State& before = path.states[k - 3];
  const State& at = path.states[k - 2];
  const Increment heading{at.u - before.u, at.lambda - before.lambda};

  const KinkLocator locator(*p.model, p.scales, f, o);
  const KinkAheadFinder finder(*p.model, p.scales, locator, o);
  const std::optional<KinkAhead> ahead = finder.Find(k, before, at, heading, 2.0 * o.arc_length);
  ASSERT_TRUE(ahead.has_value());
  EXPECT_TRUE(ahead->kink.verdict.verified);
  EXPECT_EQ(ahead->kink.pair, 0);
  EXPECT_NEAR(ahead->kink.state.lambda, t.Lambda(floor), 1e-9);
  EXPECT_NEAR(t.h + ahead->kink.state.u[p.control_dof], floor, 1e-10);
  // Along the floor: the apex stays on it, the load rises, the direction is a unit one.
  EXPECT_GT(ahead->leave.dlambda, 0.0);
  EXPECT_NEAR(ahead->leave.du[p.control_dof], 0.0, 1e-10);
  EXPECT_NEAR(HNorm(ahead->leave.du, ahead->leave.dlambda, o.lambda_weight), 1.0, 1e-12);

  // Nothing ahead within reach far from the floor.
  EXPECT_FALSE(finder
                   .Find(3, path.states[0], path.states[1],
                         {path.states[1].u - path.states[0].u,
                          path.states[1].lambda - path.states[0].lambda},
                         2.0 * o.arc_length)
                   .has_value());
}

}  // namespace
}  // namespace cb
