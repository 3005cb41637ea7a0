// How an arc-length step leaves its origin, the two strategies of ArcLengthTracer: along the
// branch (ContinuationLeg) or off a bifurcation point onto the other branch (BranchSwitchLeg).
// A leg gives each attempt its prediction, says which answers go the wrong way, and how many
// predictions are tried at each arc length before it is halved.
#pragma once

#include <utility>
#include <vector>

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
  // The row that closes attempt `attempt` (0, 1, ...) at arc length theta (step_problem.h).
  virtual StepConstraint Constraint(int attempt, double theta, double lambda_weight) const = 0;
  // The predicted increment given to attempt `attempt`, taken with arc length theta.
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
  // trail: the path traced behind the origin, as increments from it, nearest first (TurnsBack);
  // empty before the first step, when the heading is the tangent.
  ContinuationLeg(StepOrigin origin, int branch, Increment heading, std::vector<Increment> trail,
                  double lambda_weight);

  bool switches_branch() const override { return false; }
  int predictions_per_arc_length() const override { return 1; }
  // (33): the sphere of radius theta about the origin.
  StepConstraint Constraint(int attempt, double theta, double lambda_weight) const override;
  // (38), (41): the heading, rescaled to theta.
  Increment Predict(int attempt, double theta) const override;
  // The answer turns back on the path (turn_back.h).
  bool Reversed(const StepPoint& answer, double theta) const override;

 private:
  Increment heading_;
  std::vector<Increment> trail_;
  double lambda_weight_;
};

// Off a located bifurcation point onto the other branch (docs/method.md section 5): the step
// is closed by the hyperplane orthogonal to the null vector at distance theta from the point,
// lambda free (Riks; Wagner & Wriggers 1988), not by the sphere (33). The null vector is
// orthogonal to the traced branch's tangent there, so that branch meets the plane only far from
// the point (on a symmetric problem, never: its states have no component along the mode), and
// the root nearest the prediction is the other branch's crossing. Both senses of the null
// vector are tried before theta is cut. The origin has no unstable-mode count (an eigenvalue is
// zero there) and no previous step on the new branch.
class BranchSwitchLeg final : public StepLeg {
 public:
  // `bifurcation`: its state and null vector `mode`; `new_branch`: the branch it leads onto.
  BranchSwitchLeg(const CriticalPointRecord& bifurcation, int new_branch);

  bool switches_branch() const override { return true; }
  int predictions_per_arc_length() const override { return 2; }
  // The hyperplane mode . du = theta, the mode in the sense + for even attempts, - for odd.
  StepConstraint Constraint(int attempt, double theta, double lambda_weight) const override;
  // theta times the null vector in the attempt's sense, at constant load.
  Increment Predict(int attempt, double theta) const override;
  // Never: the plane has no wrong side (each sense is a plane of its own), and it does not meet
  // the branch already traced near the point. How far the answer is from the point is no test:
  // on P2 the new branch falls in load as 40 times the square of the mode's amplitude, so its
  // crossing of the plane at theta = 0.1 is 5 theta away.
  bool Reversed(const StepPoint& answer, double theta) const override;

 private:
  double Sense(int attempt) const { return attempt % 2 == 0 ? 1.0 : -1.0; }

  Vec mode_;
};

}  // namespace cb
