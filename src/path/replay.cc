#include "path/replay.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "path/step_solve.h"

namespace cb {

void PathRecorder::OnAttempt(const StepAttempt& attempt) {
  if (!attempt.accepted) return;
  states.push_back(attempt.state);
  increments.push_back(attempt.result.point);
  StepPoint prediction;
  prediction.du = attempt.predicted_du;
  prediction.dlambda = attempt.predicted_dlambda;
  predictions.push_back(prediction);
  arc_lengths.push_back(attempt.arc_length);
  kinds.push_back(attempt.kind);
}

PathSummary ReplayPath(const ContactModel& model, const ContactScales& scales, const State& initial,
                       const PathRecorder& reference, Formulation& formulation,
                       const PathOptions& options, PathObserver* observer) {
  options.Validate();
  PathSummary summary;
  summary.final_state = initial;
  const int steps = static_cast<int>(reference.states.size());
  const double w = options.lambda_weight;
  std::any previous_warm_state;
  for (int k = 1; k <= steps; ++k) {
    const State& base = k == 1 ? initial : reference.states[k - 2];
    const ConstraintKind kind = reference.kinds[k - 1];
    StepConstraint constraint =
        kind == ConstraintKind::kFixedLoad
            ? StepConstraint::FixedLoad(base.lambda + reference.increments[k - 1].dlambda)
            : StepConstraint::ArcLength(reference.arc_lengths[k - 1], w);
    StepProblem problem{&model, base, constraint, scales};

    StartPoint start;
    start.kind = options.start;
    start.r = base.r;
    start.warm_state = previous_warm_state;
    start.du = reference.predictions[k - 1].du;
    start.dlambda = reference.predictions[k - 1].dlambda;

    StepAttempt attempt;
    attempt.step = k;
    attempt.kind = kind;
    attempt.arc_length = kind == ConstraintKind::kArcLength ? constraint.arc_length : 0.0;
    JudgedStep judged = SolveAndJudge(formulation, problem, start, options);
    ++summary.attempts;
    attempt.result = std::move(judged.result);
    attempt.verdict = judged.verdict;
    attempt.state = std::move(judged.state);
    attempt.n_contact = judged.n_contact;
    const StepPoint& point = attempt.result.point;
    // The reference direction decides "forward": the answer must not point against the
    // reference step (the other root of (33)).
    const StepPoint& ref = reference.increments[k - 1];
    attempt.reversed = kind == ConstraintKind::kArcLength &&
                       point.du.dot(ref.du) + w * w * point.dlambda * ref.dlambda <= 0.0;
    attempt.accepted = attempt.verdict.verified && !attempt.reversed;
    if (observer != nullptr) observer->OnAttempt(attempt);
    if (attempt.accepted) {
      ++summary.accepted_steps;
      summary.final_state = attempt.state;
      previous_warm_state = attempt.result.warm_state;
    } else {
      previous_warm_state.reset();  // a failed step's backend state is no start for the next one
    }
    if (attempt.result.status == Status::kStoppedByCaller ||
        (options.controls.interrupted && options.controls.interrupted())) {
      summary.status = Status::kStoppedByCaller;
      summary.message = "stopped by the caller at step " + std::to_string(k);
      return summary;
    }
  }
  summary.status = summary.accepted_steps == steps ? Status::kConverged : Status::kFailed;
  summary.message = std::to_string(summary.accepted_steps) + " of " + std::to_string(steps) +
                    " replayed steps verified";
  return summary;
}

}  // namespace cb
