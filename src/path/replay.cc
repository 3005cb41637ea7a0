#include "path/replay.h"

#include <any>
#include <string>

#include "path/arc_length_norm.h"
#include "path/step_solve.h"

namespace cb {

PathSummary ReplayPath(const ContactModel& model, const ContactScales& scales, const State& initial,
                       const PathRecorder& reference, Formulation& formulation,
                       const PathOptions& options, PathObserver* observer) {
  options.Validate();
  PathSummary summary;
  summary.final_state = initial;
  const int steps = static_cast<int>(reference.steps.size());
  const double w = options.lambda_weight;
  std::any previous_warm_state;
  for (int k = 1; k <= steps; ++k) {
    const RecordedStep& reference_step = reference.steps[k - 1];
    const State& base = k == 1 ? initial : reference.steps[k - 2].state;
    const ConstraintKind kind = reference_step.kind;
    StepConstraint constraint =
        kind == ConstraintKind::kFixedLoad
            ? StepConstraint::FixedLoad(base.lambda + reference_step.increment.dlambda)
            : StepConstraint::ArcLength(reference_step.arc_length, w);
    StepProblem problem{&model, base, constraint, scales};

    StartPoint start;
    start.kind = options.start;
    start.r = base.r;
    start.warm_state = previous_warm_state;
    start.du = reference_step.prediction.du;
    start.dlambda = reference_step.prediction.dlambda;

    StepAttempt attempt;
    attempt.step = k;
    attempt.kind = kind;
    attempt.arc_length = kind == ConstraintKind::kArcLength ? constraint.arc_length : 0.0;
    RecordJudgedStep(SolveAndJudge(formulation, problem, start, options), &attempt);
    ++summary.attempts;
    const StepPoint& point = attempt.result.point;
    // The reference direction decides "forward": the answer must not point against the
    // reference step (the other root of (33)).
    const StepPoint& ref = reference_step.increment;
    attempt.reversed = kind == ConstraintKind::kArcLength &&
                       HInner(point.du, point.dlambda, ref.du, ref.dlambda, w) <= 0.0;
    attempt.accepted = SolvedAndVerified(attempt.result, attempt.verdict) && !attempt.reversed;
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
