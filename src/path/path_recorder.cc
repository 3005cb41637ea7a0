#include "path/path_recorder.h"

#include <utility>

namespace cb {

void PathRecorder::OnAttempt(const StepAttempt& attempt) {
  if (!attempt.accepted) return;
  RecordedStep step;
  step.state = attempt.state;
  step.increment = attempt.result.point;
  step.prediction.du = attempt.predicted_du;
  step.prediction.dlambda = attempt.predicted_dlambda;
  step.across_contact_change = attempt.across_contact_change;
  step.arc_length = attempt.arc_length;
  step.kind = attempt.kind;
  step.switch_origin = attempt.switch_origin;
  step.plane_normal = attempt.plane_normal;
  steps.push_back(std::move(step));
}

}  // namespace cb
