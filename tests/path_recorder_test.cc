// PathRecorder (path/path_recorder.h) and ReplayPath (path/replay.h) on the two-bar truss
// snapping onto a floor (a path with a kink).
#include "path/path_recorder.h"

#include <gtest/gtest.h>

#include <vector>

#include "formulations/implicit_fb/implicit_fb.h"
#include "path/replay.h"
#include "problems/problem.h"

namespace cb {
namespace {

// Records every accepted attempt beside a PathRecorder.
class Tee final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& a) override {
    recorder.OnAttempt(a);
    if (a.accepted) accepted.push_back(a);
  }
  void OnKink(const KinkRecord& k) override { recorder.OnKink(k); }
  PathRecorder recorder;
  std::vector<StepAttempt> accepted;
};

class PathRecorderTest : public ::testing::Test {
 protected:
  PathRecorderTest() : p_(MakeProblem("two-bar-obstacle")) {
    options_.arc_length = 0.02;
    options_.max_steps = 80;
    ImplicitFb f;
    summary_ = TraceArcLengthPath(*p_.model, p_.scales, ZeroState(*p_.model), f, options_, &tee_);
  }

  Problem p_;
  PathOptions options_;
  Tee tee_;
  PathSummary summary_;
};

TEST_F(PathRecorderTest, EachAcceptedStepIsRecordedOnce) {
  ASSERT_EQ(summary_.status, Status::kConverged) << summary_.message;
  const PathRecorder& r = tee_.recorder;
  ASSERT_EQ(r.steps.size(), 80u);
  ASSERT_EQ(tee_.accepted.size(), 80u);
  EXPECT_EQ(r.kinks.size(), 1u);
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const StepAttempt& a = tee_.accepted[k];
    const RecordedStep& s = r.steps[k];
    EXPECT_EQ(s.state.u, a.state.u);
    EXPECT_EQ(s.state.lambda, a.state.lambda);
    EXPECT_EQ(s.increment.du, a.result.point.du);
    EXPECT_EQ(s.prediction.du, a.predicted_du);
    EXPECT_EQ(s.prediction.dlambda, a.predicted_dlambda);
    EXPECT_EQ(s.across_contact_change, a.across_contact_change);
    EXPECT_EQ(s.arc_length, a.arc_length);
    EXPECT_EQ(s.kind, ConstraintKind::kArcLength);
  }
}

// The step within which the floor is met was predicted along both pieces of the path
// (corner_prediction.h): the switching function of the apex, extrapolated from the last two
// states, runs to zero within it.
TEST_F(PathRecorderTest, TheStepOntoTheFloorIsPredictedAcrossTheContactChange) {
  ASSERT_EQ(tee_.recorder.kinks.size(), 1u);
  const int kink_step = tee_.recorder.kinks[0].step;
  EXPECT_TRUE(tee_.recorder.steps[kink_step - 1].across_contact_change);
  EXPECT_FALSE(tee_.recorder.steps[kink_step - 3].across_contact_change);
}

// The formulation that traced the path, given the same steps with the same starts, finds the
// same states with the same work.
TEST_F(PathRecorderTest, ReplayingThePathWithItsOwnFormulationReproducesIt) {
  ImplicitFb f;
  Tee replayed;
  const PathSummary s =
      ReplayPath(*p_.model, p_.scales, ZeroState(*p_.model), tee_.recorder, f, options_, &replayed);
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  ASSERT_EQ(replayed.accepted.size(), tee_.recorder.steps.size());
  for (std::size_t k = 0; k < replayed.accepted.size(); ++k) {
    const State& a = replayed.accepted[k].state;
    const State& b = tee_.recorder.steps[k].state;
    EXPECT_LE((a.u - b.u).lpNorm<Eigen::Infinity>(), 1e-12) << "step " << k + 1;
    EXPECT_NEAR(a.lambda, b.lambda, 1e-12) << "step " << k + 1;
    EXPECT_EQ(replayed.accepted[k].result.counts.iterations,
              tee_.accepted[k].result.counts.iterations)
        << "step " << k + 1;
  }
}

}  // namespace
}  // namespace cb
