// The arc-length tracer's branch switch (path/arc_length_tracer.h) where it fails: on the
// report's P2 with the quasi-Newton solver and theta = 0.5, every attempt along the null vector
// of the bifurcation point returns to the branch already traced, and the path goes on along it.
#include "path/arc_length_tracer.h"

#include <gtest/gtest.h>

#include <vector>

#include "formulations/implicit_fb/implicit_fb.h"
#include "problems/problem.h"

namespace cb {
namespace {

class Collector final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& a) override { attempts.push_back(a); }
  void OnCriticalPoint(const CriticalPointRecord& c) override { critical.push_back(c); }
  std::vector<StepAttempt> attempts;
  std::vector<CriticalPointRecord> critical;
};

TEST(ArcLengthTracerTest, AFailedBranchSwitchIsRecordedAndThePathGoesOnAlongItsBranch) {
  const Problem p = MakeProblem("arch-flat");
  ImplicitFbOptions fo;
  fo.solver = "quasi-newton";
  ImplicitFb f(fo);
  PathOptions o;
  o.arc_length = 0.6;  // one at which the switch fails (which ones do moves with rounding)
  o.max_steps = 200;
  o.bifurcations = BifurcationMode::kSwitch;
  Collector c;
  const PathSummary s = ArcLengthTracer(*p.model, p.scales, f, o, &c).Run(ZeroState(*p.model));
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  EXPECT_EQ(s.accepted_steps, 200);
  EXPECT_EQ(s.branch_switches, 0);

  // The bifurcation point marked for the switch, then the same point reported as not switched.
  const CriticalPointRecord* marked = nullptr;
  const CriticalPointRecord* failed = nullptr;
  for (const CriticalPointRecord& cp : c.critical) {
    if (cp.switched) marked = &cp;
    if (marked != nullptr && &cp != marked && !cp.switched && cp.state.u == marked->state.u) {
      failed = &cp;
    }
  }
  ASSERT_NE(marked, nullptr);
  ASSERT_NE(failed, nullptr);
  EXPECT_EQ(marked->kind, CriticalPointRecord::Kind::kBifurcation);
  EXPECT_EQ(failed->step, marked->step);
  EXPECT_NE(failed->message.find("branch switch failed"), std::string::npos);

  // Every switch attempt: the step after the bifurcation point, rejected, both senses of the
  // null vector at each theta before it is halved, max_cutbacks + 1 arc lengths.
  std::vector<StepAttempt> switches;
  for (const StepAttempt& a : c.attempts) {
    if (a.branch_switch) switches.push_back(a);
  }
  ASSERT_EQ(switches.size(), 2u * (o.max_cutbacks + 1));
  for (std::size_t k = 0; k < switches.size(); ++k) {
    const StepAttempt& a = switches[k];
    EXPECT_EQ(a.step, marked->step + 1);
    EXPECT_EQ(a.attempt, static_cast<int>(k));
    EXPECT_EQ(a.branch, 1);
    EXPECT_FALSE(a.accepted);
    EXPECT_EQ(a.predicted_dlambda, 0.0);
    EXPECT_NEAR((a.predicted_du - (k % 2 == 0 ? 1.0 : -1.0) * a.arc_length * marked->mode).norm(),
                0.0, 1e-15);
    if (k % 2 == 1) {
      EXPECT_EQ(a.arc_length, switches[k - 1].arc_length);
    } else if (k >= 2) {
      EXPECT_EQ(a.arc_length, 0.5 * switches[k - 2].arc_length);
    }
  }

  // The step is then taken along the branch already traced, at the nominal arc length.
  for (const StepAttempt& a : c.attempts) {
    if (!a.accepted) continue;
    EXPECT_EQ(a.branch, 0);
    EXPECT_FALSE(a.branch_switch);
    if (a.step == marked->step + 1) {
      EXPECT_EQ(a.arc_length, o.arc_length);
    }
  }
}

}  // namespace
}  // namespace cb
