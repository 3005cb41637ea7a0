#include "path/step_leg.h"

#include <utility>

#include "path/turn_back.h"

namespace cb {

ContinuationLeg::ContinuationLeg(StepOrigin origin, int branch, Increment heading,
                                 std::vector<Increment> trail, double lambda_weight)
    : StepLeg(std::move(origin), branch),
      heading_(std::move(heading)),
      trail_(std::move(trail)),
      lambda_weight_(lambda_weight) {}

StepConstraint ContinuationLeg::Constraint(int /*attempt*/, double theta,
                                           double lambda_weight) const {
  return StepConstraint::ArcLength(theta, lambda_weight);
}

Increment ContinuationLeg::Predict(int /*attempt*/, double theta) const {
  const double scale = theta / HNorm(heading_.du, heading_.dlambda, lambda_weight_);
  return {heading_.du * scale, heading_.dlambda * scale};
}

bool ContinuationLeg::Reversed(const StepPoint& answer, double theta) const {
  return TurnsBack(answer, heading_, trail_, theta, lambda_weight_);
}

BranchSwitchLeg::BranchSwitchLeg(const CriticalPointRecord& bifurcation, int new_branch)
    : StepLeg(StepOrigin{bifurcation.state, -1, std::nullopt}, new_branch),
      mode_(bifurcation.mode) {}

StepConstraint BranchSwitchLeg::Constraint(int attempt, double theta,
                                           double /*lambda_weight*/) const {
  return StepConstraint::Hyperplane(Sense(attempt) * mode_, 0.0, theta);
}

Increment BranchSwitchLeg::Predict(int attempt, double theta) const {
  return {mode_ * (Sense(attempt) * theta), 0.0};
}

bool BranchSwitchLeg::Reversed(const StepPoint& /*answer*/, double /*theta*/) const {
  return false;
}

}  // namespace cb
