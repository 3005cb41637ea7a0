// Replay mode of the comparison protocol (COMPARISON.md "Same work for everyone"): every
// formulation solves the SAME steps, each starting from the reference path's previous accepted
// state, so that a failure at step k does not change the work given at step k + 1.
#pragma once

#include <vector>

#include "path/path.h"

namespace cb {

// The accepted states of a path and the increments that led to them, recorded by observing
// TraceArcLengthPath (or SolveFixedLoad).
class PathRecorder final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& attempt) override;
  void OnKink(const KinkRecord& kink) override { kinks.push_back(kink); }

  // states[k] is the state after accepted step k + 1; increments[k] the increment of that step
  // (du, r, dlambda), predictions[k] the predicted increment its warm start was given, and
  // arc_lengths[k] the theta it was taken with.
  std::vector<State> states;
  std::vector<StepPoint> increments;
  std::vector<StepPoint> predictions;
  std::vector<double> arc_lengths;
  std::vector<ConstraintKind> kinds;
  std::vector<KinkRecord> kinks;
};

// Replays the reference path's steps with `formulation`. Step k (1-based) starts from the
// reference state after step k - 1 (the initial state for k = 1) with the reference step's own
// constraint (its theta for arc length, or the fixed load); a warm start gets the prediction
// the reference step itself was given (the previous increment, the tangent predictor on the
// first step, or the direction from a kink) and the reference reactions, plus
// this formulation's own backend state from its previous step when that step verified. Every
// step is attempted once (no cut-back) and judged; failures do not stop the replay. Each is
// reported through observer->OnAttempt with attempt = 0.
PathSummary ReplayPath(const ContactModel& model, const ContactScales& scales, const State& initial,
                       const PathRecorder& reference, Formulation& formulation,
                       const PathOptions& options, PathObserver* observer);

}  // namespace cb
