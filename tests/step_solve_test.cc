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

  JudgedStep Solve(Formulation& f, const State& base, const StepConstraint& constraint,
                   int repeats = 1) const {
    StartPoint start;
    start.du = Vec::Zero(p_.model->num_dofs());
    start.r = base.r;
    PathOptions options;
    options.solve_repeats = repeats;
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

// ImplicitFb whose `changed_call`-th solve (from 1) claims one more iteration and moves its
// answer by `shift`: a formulation whose repetitions do not agree.
class DriftingImplicitFb final : public Formulation {
 public:
  DriftingImplicitFb(int changed_call, double shift) : changed_call_(changed_call), shift_(shift) {}
  std::string name() const override { return "drifting"; }
  std::string solver() const override { return inner_.solver(); }
  std::string settings() const override { return inner_.settings(); }
  int calls() const { return calls_; }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    *result = inner_.Solve(step, start, controls);
    if (++calls_ != changed_call_) return;
    result->counts.iterations += shift_ == 0.0 ? 1 : 0;
    result->point.du.array() += shift_;
  }
  ImplicitFb inner_;
  int changed_call_;
  double shift_;
  int calls_ = 0;
};

// compare --repeat: N solves from the same start, the first answer kept, its time the median
// of the N with their range.
TEST_F(StepSolveTest, ARepeatedSolveKeepsTheFirstAnswerWithTheMedianTimeAndItsRange) {
  const State base = bar_.StateAt(0.5 * bar_.lambda_c);
  const StepConstraint load = StepConstraint::FixedLoad(1.5 * bar_.lambda_c);
  ImplicitFb once;
  const JudgedStep single = Solve(once, base, load);
  ASSERT_TRUE(single.verdict.verified) << single.result.message;
  EXPECT_EQ(single.result.time_samples, 1);
  EXPECT_EQ(single.result.time_min_s, single.result.time_s);
  EXPECT_EQ(single.result.time_max_s, single.result.time_s);

  DriftingImplicitFb steady(/*changed_call=*/0, 0.0);  // never changes
  const JudgedStep repeated = Solve(steady, base, load, 5);
  EXPECT_EQ(steady.calls(), 5);
  EXPECT_EQ(repeated.result.time_samples, 5);
  EXPECT_LE(repeated.result.time_min_s, repeated.result.time_s);
  EXPECT_LE(repeated.result.time_s, repeated.result.time_max_s);
  EXPECT_TRUE(repeated.result.repeats_disagreement.empty()) << repeated.result.repeats_disagreement;
  EXPECT_TRUE(repeated.verdict.verified);
  EXPECT_EQ(repeated.result.counts.iterations, single.result.counts.iterations);
}

// A repetition that disagrees is said (the first one that does), and the first answer is still
// the one kept and judged.
TEST_F(StepSolveTest, ARepetitionThatDisagreesIsSaidAndTheFirstAnswerIsKept) {
  const State base = bar_.StateAt(0.5 * bar_.lambda_c);
  const StepConstraint load = StepConstraint::FixedLoad(1.5 * bar_.lambda_c);
  DriftingImplicitFb reference(0, 0.0);
  const JudgedStep first = Solve(reference, base, load);

  DriftingImplicitFb more_iterations(/*changed_call=*/3, 0.0);
  const JudgedStep a = Solve(more_iterations, base, load, 4);
  EXPECT_EQ(a.result.repeats_disagreement.rfind("repetition 3: ", 0), 0u)
      << a.result.repeats_disagreement;
  EXPECT_EQ(a.result.counts.iterations, first.result.counts.iterations);
  EXPECT_EQ(a.result.time_samples, 4);

  DriftingImplicitFb moved(/*changed_call=*/2, 1e-3);  // far beyond the tolerance 1e-8
  const JudgedStep b = Solve(moved, base, load, 3);
  EXPECT_NE(b.result.repeats_disagreement.find("repetition 2: an answer"), std::string::npos)
      << b.result.repeats_disagreement;
  EXPECT_EQ(b.result.point.du, first.result.point.du);
  EXPECT_TRUE(b.verdict.verified);

  DriftingImplicitFb within(/*changed_call=*/2, 1e-13);  // within the tolerance: agrees
  EXPECT_TRUE(Solve(within, base, load, 3).result.repeats_disagreement.empty());
}

}  // namespace
}  // namespace cb
