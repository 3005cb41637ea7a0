// The accepted steps of a path, recorded by observing TraceArcLengthPath (or SolveFixedLoad):
// the reference path a replay gives every formulation (replay.h).
#pragma once

#include <optional>
#include <vector>

#include "path/path.h"

namespace cb {

// One accepted step.
struct RecordedStep {
  State state;           // the state after the step
  StepPoint increment;   // (du, r, dlambda) of the step
  StepPoint prediction;  // the predicted increment (du, dlambda) its warm start was given
  bool across_contact_change = false;  // that prediction was bent at a contact change
  double arc_length = 0.0;             // theta it was taken with (arc-length steps)
  ConstraintKind kind = ConstraintKind::kArcLength;
  // kHyperplane: the bifurcation point the step left from and its plane's unit normal.
  std::optional<State> switch_origin;
  Vec plane_normal;
};

class PathRecorder final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& attempt) override;
  void OnKink(const KinkRecord& kink) override { kinks.push_back(kink); }

  // steps[k] is accepted step k + 1.
  std::vector<RecordedStep> steps;
  std::vector<KinkRecord> kinks;
};

}  // namespace cb
