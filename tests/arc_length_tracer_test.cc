// The arc-length tracer's branch switch (path/arc_length_tracer.h) on the report's P2: the step
// off the bifurcation point C is closed by the plane orthogonal to its null vector, which the
// symmetric branch does not cross, so the switch lands on the asymmetric branch D whatever the
// solver and the arc length (scripts/sweep_branch_switch.py sweeps the whole matrix). When every
// attempt off the point fails (forced here), the failure is recorded and the path goes on along
// its branch.
#include "path/arc_length_tracer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
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

PathOptions SwitchOptions(double theta, int steps) {
  PathOptions o;
  o.arc_length = theta;
  o.max_steps = steps;
  o.bifurcations = BifurcationMode::kSwitch;
  return o;
}

// The bifurcation point marked for the switch.
const CriticalPointRecord* Marked(const Collector& c) {
  for (const CriticalPointRecord& cp : c.critical) {
    if (cp.switched) return &cp;
  }
  return nullptr;
}

// theta = 0.6 with Broyden's solver is where the old switch along the null vector on the sphere
// (33) returned to the symmetric branch.
TEST(ArcLengthTracerTest, TheSwitchOffCLandsOnTheAsymmetricBranchOnItsPlane) {
  const Problem p = MakeProblem("arch-flat");
  for (const std::string solver : {"newton", "quasi-newton"}) {
    SCOPED_TRACE(solver);
    ImplicitFbOptions fo;
    fo.solver = solver;
    ImplicitFb f(fo);
    const PathOptions o = SwitchOptions(0.6, 200);
    Collector c;
    const PathSummary s = ArcLengthTracer(*p.model, p.scales, f, o, &c).Run(ZeroState(*p.model));
    ASSERT_EQ(s.status, Status::kConverged) << s.message;
    EXPECT_EQ(s.branch_switches, 1);
    const CriticalPointRecord* marked = Marked(c);
    ASSERT_NE(marked, nullptr);
    EXPECT_EQ(marked->kind, CriticalPointRecord::Kind::kBifurcation);

    int off_c = 0;
    for (const StepAttempt& a : c.attempts) {
      if (!a.branch_switch) continue;
      ++off_c;
      EXPECT_EQ(a.kind, ConstraintKind::kHyperplane);
      EXPECT_EQ(a.step, marked->step + 1);
      ASSERT_TRUE(a.switch_origin.has_value());
      // The answer lies on its plane, at distance theta along the mode from C.
      const Vec du = a.state.u - a.switch_origin->u;
      EXPECT_NEAR(a.plane_normal.dot(du) / a.arc_length, 1.0, 1e-9);
      EXPECT_NEAR(std::abs(a.plane_normal.dot(marked->mode)), 1.0, 1e-12);
      EXPECT_TRUE(a.accepted);
    }
    EXPECT_EQ(off_c, 1);
    // Every accepted step after C is on branch 1 and moves along the mode away from C.
    double amplitude = 0.0;
    for (const StepAttempt& a : c.attempts) {
      if (!a.accepted || a.step <= marked->step) continue;
      EXPECT_EQ(a.branch, 1);
      const double next = std::abs(marked->mode.dot(a.state.u - marked->state.u));
      if (a.step <= marked->step + 5) {
        EXPECT_GT(next, amplitude);
      }
      amplitude = next;
    }
  }
}

// A formulation that answers every step closed by a hyperplane with no increment, which the
// verdict refuses (the plane's row is 1): the switch off C cannot succeed.
class NoPlanes final : public Formulation {
 public:
  std::string name() const override { return inner_.name(); }
  std::string solver() const override { return inner_.solver(); }
  std::string settings() const override { return inner_.settings(); }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    *result = inner_.Solve(step, start, controls);
    if (step.constraint.kind == ConstraintKind::kHyperplane) {
      result->status = Status::kFailed;
      result->message = "refused by the test";
      result->point.du.setZero();
      result->point.dlambda = 0.0;
    }
  }
  ImplicitFb inner_;
};

TEST(ArcLengthTracerTest, AFailedBranchSwitchIsRecordedAndThePathGoesOnAlongItsBranch) {
  const Problem p = MakeProblem("arch-flat");
  NoPlanes f;
  const PathOptions o = SwitchOptions(0.5, 200);
  Collector c;
  const PathSummary s = ArcLengthTracer(*p.model, p.scales, f, o, &c).Run(ZeroState(*p.model));
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  EXPECT_EQ(s.accepted_steps, 200);
  EXPECT_EQ(s.branch_switches, 0);

  // The bifurcation point marked for the switch, then the same point reported as not switched.
  const CriticalPointRecord* marked = Marked(c);
  const CriticalPointRecord* failed = nullptr;
  for (const CriticalPointRecord& cp : c.critical) {
    if (marked != nullptr && &cp != marked && !cp.switched && cp.state.u == marked->state.u) {
      failed = &cp;
    }
  }
  ASSERT_NE(marked, nullptr);
  ASSERT_NE(failed, nullptr);
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
    const double sense = k % 2 == 0 ? 1.0 : -1.0;
    EXPECT_NEAR((a.predicted_du - sense * a.arc_length * marked->mode).norm(), 0.0, 1e-15);
    EXPECT_NEAR((a.plane_normal - sense * marked->mode).norm(), 0.0, 1e-15);
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
