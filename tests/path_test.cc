// The arc-length driver against closed-form paths (PROBLEMS.md verification problems), the
// kink location of METHOD.md section 6, step cut-back and the report's P3 path.
#include "path/path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fixtures.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "problems/problem.h"

namespace cb {
namespace {

// Keeps every attempt and kink.
class Collector final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& a) override { attempts.push_back(a); }
  void OnKink(const KinkRecord& k) override { kinks.push_back(k); }
  std::vector<StepAttempt> Accepted() const {
    std::vector<StepAttempt> out;
    for (const auto& a : attempts) {
      if (a.accepted) out.push_back(a);
    }
    return out;
  }
  std::vector<StepAttempt> attempts;
  std::vector<KinkRecord> kinks;
};

PathSummary Trace(const Problem& p, Formulation& f, int steps, Collector* c, double theta = 0.0) {
  PathOptions o;
  o.arc_length = theta > 0.0 ? theta : p.arc_length;
  o.max_steps = steps;
  return TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), f, o, c);
}

using testing::TwoBarOf;

TEST(PathTest, BarAgainstWallFollowsItsClosedForm) {
  const Problem p = MakeProblem("bar-wall");
  ImplicitFb f;
  Collector c;
  const PathSummary s = Trace(p, f, p.steps, &c);
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  const double ea = p.parameters.Real("axial_stiffness");
  const double gap = p.parameters.Real("gap");
  const double length = p.parameters.Real("length");
  const double lambda_c = ea * gap / length;  // P = 1
  bool contact_seen = false;
  for (const StepAttempt& a : c.Accepted()) {
    const double u = a.state.u[p.control_dof];
    if (a.state.lambda < lambda_c) {
      EXPECT_NEAR(u, a.state.lambda * length / ea, 1e-10);
      EXPECT_NEAR(a.state.r[0], 0.0, 1e-10);
    } else {
      contact_seen = true;
      EXPECT_NEAR(u, gap, 1e-10);
      EXPECT_NEAR(a.state.r[0], -(a.state.lambda - ea * gap / length), 1e-8);
    }
  }
  EXPECT_TRUE(contact_seen);
  // The contact change is a kink at lambda_c with g = r = 0.
  ASSERT_EQ(c.kinks.size(), 1u);
  EXPECT_TRUE(c.kinks[0].verdict.verified);
  EXPECT_TRUE(c.kinks[0].between);
  EXPECT_NEAR(c.kinks[0].state.lambda, lambda_c, 1e-8);
}

TEST(PathTest, TwoBarSnapThroughMatchesClosedFormThroughTheLimitPoint) {
  const Problem p = MakeProblem("two-bar");
  const testing::TwoBarClosedForm t = TwoBarOf(p);
  ImplicitFb f;
  Collector c;
  const double theta = 0.02;
  const PathSummary s = Trace(p, f, 120, &c, theta);
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  double max_lambda = -1e300;
  double min_w = 1e300;
  for (const StepAttempt& a : c.Accepted()) {
    const double w = t.h + a.state.u[p.control_dof];
    EXPECT_NEAR(a.state.lambda, t.Lambda(w), 1e-9) << "w = " << w;
    if (w > 0.0) max_lambda = std::max(max_lambda, a.state.lambda);  // before the snap
    min_w = std::min(min_w, w);
  }
  // The path went past the limit point (and past the flat position w = 0).
  EXPECT_LT(min_w, -t.LimitHeight());
  // Its highest sampled load is the closed-form limit load to O(theta^2).
  const double limit = t.Lambda(t.LimitHeight());
  EXPECT_LE(max_lambda, limit + 1e-12);
  EXPECT_GT(max_lambda, limit * (1.0 - 1e-3));
}

TEST(PathTest, TwoBarOntoAFloorHasAKinkWhereTheClosedFormSaysSo) {
  const Problem p = MakeProblem("two-bar-obstacle");
  const testing::TwoBarClosedForm t = TwoBarOf(p);
  const double floor = p.parameters.Real("floor_height");
  ImplicitFb f;
  Collector c;
  const PathSummary s = Trace(p, f, 80, &c, 0.02);
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  bool touched = false;
  for (const StepAttempt& a : c.Accepted()) {
    const double w = t.h + a.state.u[p.control_dof];
    if (a.state.r[0] < -1e-9 || std::abs(w - floor) < 1e-9) {
      touched = true;
      EXPECT_NEAR(w, floor, 1e-9);
      // r = -(lambda - lambda(floor)) P with P = 1.
      EXPECT_NEAR(a.state.r[0], -(a.state.lambda - t.Lambda(floor)), 1e-8);
    } else {
      EXPECT_NEAR(a.state.lambda, t.Lambda(w), 1e-9);
    }
  }
  EXPECT_TRUE(touched);
  ASSERT_EQ(c.kinks.size(), 1u);
  const KinkRecord& k = c.kinks[0];
  EXPECT_TRUE(k.verdict.verified);
  EXPECT_TRUE(k.between);
  EXPECT_NEAR(k.state.lambda, t.Lambda(floor), 1e-8);
  EXPECT_NEAR(t.h + k.state.u[p.control_dof], floor, 1e-9);
}

TEST(PathTest, TangentPredictorIsOnTheArcAndLoads) {
  const Problem p = MakeProblem("arch-flat");
  Vec du;
  double dlambda = 0.0;
  std::string why;
  ASSERT_TRUE(
      TangentPredictor(*p.model, p.scales, ZeroState(*p.model), 0.1, 1.0, &du, &dlambda, &why))
      << why;
  EXPECT_GT(dlambda, 0.0);
  EXPECT_NEAR(std::sqrt(du.squaredNorm() + dlambda * dlambda), 0.1, 1e-14);
  // K du = f dlambda (no contact is closed at the start).
  SpMat k;
  p.model->Stiffness(Vec::Zero(p.model->num_dofs()), &k);
  EXPECT_LT((k * du - dlambda * p.model->load_pattern()).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(PathTest, AStepThatCannotBeSolvedIsCutBackThenTheRunStops) {
  const Problem p = MakeProblem("two-bar");
  ImplicitFbOptions o;
  o.solver_options.max_iterations = 1;  // Newton cannot reach 1e-8 in one iteration
  ImplicitFb f(o);
  Collector c;
  PathOptions opts;
  opts.arc_length = 0.5;
  opts.max_steps = 3;
  opts.max_cutbacks = 2;
  const PathSummary s = TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), f, opts, &c);
  EXPECT_EQ(s.status, Status::kFailed);
  EXPECT_NE(s.message.find("cut-backs"), std::string::npos) << s.message;
  ASSERT_EQ(c.attempts.size(), 3u);  // theta, theta/2, theta/4
  EXPECT_DOUBLE_EQ(c.attempts[1].arc_length, 0.25);
  EXPECT_DOUBLE_EQ(c.attempts[2].arc_length, 0.125);
  for (const auto& a : c.attempts) EXPECT_FALSE(a.accepted);
}

TEST(PathTest, InterruptStopsBetweenSteps) {
  const Problem p = MakeProblem("two-bar");
  ImplicitFb f;
  Collector c;
  PathOptions o;
  o.max_steps = 50;
  o.arc_length = 0.02;
  int polls = 0;
  o.controls.interrupted = [&polls] { return ++polls > 40; };
  const PathSummary s = TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), f, o, &c);
  EXPECT_EQ(s.status, Status::kStoppedByCaller);
  EXPECT_LT(s.accepted_steps, 50);
}

// Issue 2: the first 300 arc-length steps of P3 all verified with Newton.
TEST(PathTest, ArchCurvedFirst300StepsAllVerifiedWithNewton) {
  const Problem p = MakeProblem("arch-curved");
  ImplicitFb f;
  Collector c;
  PathOptions o;
  o.arc_length = p.arc_length;
  o.max_steps = 300;
  o.max_cutbacks = 0;  // every step must verify at the report's theta
  const PathSummary s = TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), f, o, &c);
  EXPECT_EQ(s.status, Status::kConverged) << s.message;
  EXPECT_EQ(s.accepted_steps, 300);
  for (const auto& a : c.attempts) EXPECT_TRUE(a.verdict.verified) << "step " << a.step;
  for (const auto& k : c.kinks) {
    EXPECT_TRUE(k.verdict.verified) << "kink of pair " << k.pair << " at step " << k.step;
    EXPECT_TRUE(k.between) << "kink of pair " << k.pair << " at step " << k.step;
  }
}

}  // namespace
}  // namespace cb
