// Replay mode of the comparison protocol (COMPARISON.md "Same work for everyone"): every
// formulation solves the SAME steps, each starting from the reference path's previous accepted
// state, so that a failure at step k does not change the work given at step k + 1.
#pragma once

#include "path/path.h"
#include "path/path_recorder.h"

namespace cb {

// Step k (1-based) of a replay of `reference`: the reference state after step k - 1 (the initial
// state for k = 1, the bifurcation point for a step off one) closed by the reference step's own
// constraint (its theta for arc length, its plane off a bifurcation point, or the fixed load).
StepProblem ReplayedStep(const ContactModel& model, const ContactScales& scales,
                         const State& initial, const PathRecorder& reference, int k, double w);
// Its start: the prediction the reference step itself was given and the base's reactions.
StartPoint ReplayedStart(const StepProblem& step, const PathRecorder& reference, int k,
                         StartKind kind);
// Whether `answer` points against the reference step (the other root of (33)).
bool ReplayedReversed(const PathRecorder& reference, int k, const StepPoint& answer, double w);

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
