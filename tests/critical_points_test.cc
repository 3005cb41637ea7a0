// CriticalPointFinder (path/critical_points.h) on steps of the von Mises two-bar truss built
// from its closed form lambda(w) (apex height w; docs/problems.md): a step over the limit point
// (apex held sideways) and one over the bifurcation point of the steep truss with its apex free
// sideways, where l^3 = L w^2.
#include "path/critical_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fixtures.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "path/stability.h"
#include "problems/problem.h"

namespace cb {
namespace {

using fixtures::TwoBarOf;

class CriticalPointsTest : public ::testing::Test {
 protected:
  // The state of the symmetric branch at apex height w.
  State StateAt(const Problem& p, double w) const {
    const fixtures::TwoBarClosedForm t = TwoBarOf(p);
    State s = ZeroState(*p.model);
    s.u[p.control_dof] = w - t.h;
    s.lambda = t.Lambda(w);
    return s;
  }

  StepOrigin OriginAt(const Problem& p, double w, bool previous_loaded) const {
    StepOrigin origin;
    origin.state = StateAt(p, w);
    origin.unstable_modes = UnstableModes(*p.model, p.scales, origin.state);
    if (previous_loaded) origin.previous = StepOrigin::PreviousStep{1.0, 0, std::nullopt};
    return origin;
  }

  // The accepted step from `origin` to the symmetric branch at apex height w.
  StepAttempt StepTo(const Problem& p, const StepOrigin& origin, double w) const {
    StepAttempt taken;
    taken.step = 5;
    taken.state = StateAt(p, w);
    taken.result.point.du = taken.state.u - origin.state.u;
    taken.result.point.dlambda = taken.state.lambda - origin.state.lambda;
    taken.result.point.r = taken.state.r;
    taken.stability = UnstableModes(*p.model, p.scales, taken.state);
    return taken;
  }

  std::vector<CriticalPointRecord> Find(const Problem& p, const StepOrigin& origin,
                                        const StepAttempt& taken, bool may_switch) {
    return CriticalPointFinder(*p.model, p.scales, f_, options_).Find(origin, taken, may_switch);
  }

  ImplicitFb f_;
  PathOptions options_;
};

// Over the limit point the load turns and one mode becomes unstable; the orientation of the
// path does not change across it, so it is not a bifurcation point.
TEST_F(CriticalPointsTest, AStepOverTheLimitPointIsALimitPointOnly) {
  const Problem p = MakeProblem("two-bar");
  const double limit = TwoBarOf(p).LimitHeight();
  // From just before the limit point (loaded up to it) to well past it: the load falls.
  const StepOrigin origin = OriginAt(p, limit + 0.002, /*previous_loaded=*/true);
  const StepAttempt taken = StepTo(p, origin, limit - 0.05);
  ASSERT_EQ(origin.unstable_modes, 0);
  ASSERT_EQ(taken.stability, 1);
  ASSERT_LT(taken.result.point.dlambda, 0.0);
  const std::vector<CriticalPointRecord> critical = Find(p, origin, taken, true);
  ASSERT_EQ(critical.size(), 1u);
  EXPECT_EQ(critical[0].kind, CriticalPointRecord::Kind::kLimit);
  EXPECT_EQ(critical[0].step, 5);
  EXPECT_FALSE(critical[0].nonsmooth);
  // Located, not left at the accepted state before the turn: lambda to 1e-8 of the closed form.
  const double exact = TwoBarOf(p).Lambda(limit);
  EXPECT_TRUE(critical[0].located) << critical[0].message;
  EXPECT_NEAR(critical[0].state.lambda, exact, 1e-8 * exact);
  EXPECT_GT(std::abs(origin.state.lambda - exact), 1e-6 * exact);  // the old record was off
  EXPECT_TRUE(critical[0].verdict.verified);
}

// The load may turn within the previous step: the origin is already past the limit point
// (the load falls there), and the point is located behind it.
TEST_F(CriticalPointsTest, ALimitPointWithinThePreviousStepIsLocatedBehindTheOrigin) {
  const Problem p = MakeProblem("two-bar");
  const double limit = TwoBarOf(p).LimitHeight();
  const StepOrigin origin = OriginAt(p, limit - 0.004, /*previous_loaded=*/true);
  const StepAttempt taken = StepTo(p, origin, limit - 0.03);
  ASSERT_LT(taken.result.point.dlambda, 0.0);
  const std::vector<CriticalPointRecord> critical = Find(p, origin, taken, false);
  ASSERT_FALSE(critical.empty());
  EXPECT_EQ(critical[0].kind, CriticalPointRecord::Kind::kLimit);
  const double exact = TwoBarOf(p).Lambda(limit);
  EXPECT_TRUE(critical[0].located) << critical[0].message;
  EXPECT_NEAR(critical[0].state.lambda, exact, 1e-8 * exact);
  EXPECT_NEAR(TwoBarOf(p).h + critical[0].state.u[p.control_dof], limit, 1e-3);
}

// Without a previous step on the branch (the start of the path, or the first step off a
// bifurcation point) there is no turn of the load to see.
TEST_F(CriticalPointsTest, NoPreviousStepNoLimitPoint) {
  const Problem p = MakeProblem("two-bar");
  const double limit = TwoBarOf(p).LimitHeight();
  const StepOrigin origin = OriginAt(p, limit + 0.002, /*previous_loaded=*/false);
  EXPECT_TRUE(Find(p, origin, StepTo(p, origin, limit - 0.05), true).empty());
}

// Without a count at the origin (not watched, or a bifurcation point) no change is looked for.
TEST_F(CriticalPointsTest, NoCountAtTheOriginNoModeChange) {
  const Problem p = MakeProblem("two-bar", {{"height", "3"}, {"apex", "free"}});
  StepOrigin origin = OriginAt(p, 2.9, /*previous_loaded=*/true);
  origin.unstable_modes = -1;
  EXPECT_TRUE(Find(p, origin, StepTo(p, origin, 2.5), true).empty());
}

TEST_F(CriticalPointsTest, AStepOverTheBifurcationPointLocatesItAndItsNullVector) {
  const Problem p = MakeProblem("two-bar", {{"height", "3"}, {"apex", "free"}});
  const fixtures::TwoBarClosedForm t = TwoBarOf(p);
  const double length = std::sqrt(t.b * t.b + t.h * t.h);
  double lo = t.b * std::sqrt(2.0), hi = t.h;  // l^3 - L w^2 changes sign between them
  for (int i = 0; i < 200; ++i) {
    const double w = 0.5 * (lo + hi);
    const double l = std::sqrt(t.b * t.b + w * w);
    (l * l * l - length * w * w > 0.0 ? hi : lo) = w;
  }
  const double w_c = 0.5 * (lo + hi);
  const StepOrigin origin = OriginAt(p, w_c + 0.03, /*previous_loaded=*/true);
  const StepAttempt taken = StepTo(p, origin, w_c - 0.03);
  ASSERT_EQ(taken.stability, origin.unstable_modes + 1);
  ASSERT_GT(taken.result.point.dlambda, 0.0);  // before the limit point: no turn
  const double chord = std::hypot(taken.result.point.du.norm(), taken.result.point.dlambda);
  const int sideways = p.body->body().dofs().dof(1, 0);
  for (const bool may_switch : {false, true}) {
    SCOPED_TRACE(may_switch ? "may switch" : "may not switch");
    const std::vector<CriticalPointRecord> critical = Find(p, origin, taken, may_switch);
    ASSERT_EQ(critical.size(), 1u);
    const CriticalPointRecord& b = critical[0];
    EXPECT_EQ(b.kind, CriticalPointRecord::Kind::kBifurcation);
    EXPECT_TRUE(b.located);
    EXPECT_GT(b.bisections, 0);
    EXPECT_TRUE(b.verdict.verified);
    // Bracketed to bifurcation_tolerance times the chord.
    EXPECT_NEAR(t.h + b.state.u[p.control_dof], w_c, options_.bifurcation_tolerance * chord);
    EXPECT_NEAR(std::abs(b.mode[sideways]), 1.0, 1e-6);
    EXPECT_NEAR(b.mode.norm(), 1.0, 1e-12);
    EXPECT_EQ(b.switched, may_switch);
  }
}

}  // namespace
}  // namespace cb
