// How an arc-length step leaves its origin, the two strategies of ArcLengthTracer: along the
// branch (ContinuationLeg) or off a bifurcation point onto the other branch (BranchSwitchLeg).
// A leg gives each attempt its prediction, says which answers go the wrong way, and how many
// predictions are tried at each arc length before it is halved.
#pragma once

#include <utility>

#include "path/arc_length_norm.h"
#include "path/path.h"
#include "path/step_origin.h"

namespace cb {

class StepLeg {
 public:
  virtual ~StepLeg() = default;

  // The state the step leaves from, with what the critical-point tests compare the step with.
  const StepOrigin& origin() const { return origin_; }
  // The branch the step is on (StepAttempt::branch).
  int branch() const { return branch_; }
  // Whether the step leaves the branch it starts on (StepAttempt::branch_switch).
  virtual bool switches_branch() const = 0;
  // Predictions tried at each arc length theta before theta is halved.
  virtual int predictions_per_arc_length() const = 0;
  // The predicted increment given to attempt `attempt` (0, 1, ...), taken with arc length theta.
  virtual Increment Predict(int attempt, double theta) const = 0;
  // Whether `answer`, verified or not, goes the wrong way (StepAttempt::reversed).
  virtual bool Reversed(const StepPoint& answer, double theta) const = 0;

 protected:
  StepLeg(StepOrigin origin, int branch) : origin_(std::move(origin)), branch_(branch) {}

 private:
  StepOrigin origin_;
  int branch_;
};

// Along the branch from the last accepted state, predicted by the path's heading: the previous
// increment (or the direction from a kink past a corner), or the tangent before the first step.
class ContinuationLeg final : public StepLeg {
 public:
  // heading_is_a_step: the heading is an increment just taken (there is a segment of the path
  // to turn back onto), not the tangent.
  ContinuationLeg(StepOrigin origin, int branch, Increment heading, bool heading_is_a_step,
                  double lambda_weight);

  bool switches_branch() const override { return false; }
  int predictions_per_arc_length() const override { return 1; }
  // (38), (41): the heading, rescaled to theta.
  Increment Predict(int attempt, double theta) const override;
  // The answer turns back on the path (turn_back.h).
  bool Reversed(const StepPoint& answer, double theta) const override;

 private:
  Increment heading_;
  bool heading_is_a_step_;
  double lambda_weight_;
};

// Off a located bifurcation point along its null vector, at constant load: the root of (33)
// nearest to it is on the other branch (its tangent there is the null vector). Both senses of
// the null vector are tried before theta is cut (a solver may be drawn back to the branch
// already traced from one side and not from the other). The origin has no unstable-mode count
// (an eigenvalue is zero there) and no previous step on the new branch.
class BranchSwitchLeg final : public StepLeg {
 public:
  // `bifurcation`: its state and null vector `mode`; `new_branch`: the branch it leads onto.
  BranchSwitchLeg(const CriticalPointRecord& bifurcation, int new_branch);

  bool switches_branch() const override { return true; }
  int predictions_per_arc_length() const override { return 2; }
  // theta times the null vector, in the sense + for even attempts and - for odd ones.
  Increment Predict(int attempt, double theta) const override;
  // The answer must leave along the null vector, not return to the branch already traced.
  bool Reversed(const StepPoint& answer, double theta) const override;

 private:
  Vec mode_;
};

}  // namespace cb
