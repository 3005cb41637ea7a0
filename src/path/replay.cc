#include "path/replay.h"

#include <any>
#include <string>

#include "path/arc_length_norm.h"
#include "path/step_solve.h"

namespace cb {

StepProblem ReplayedStep(const ContactModel& model, const ContactScales& scales,
                         const State& initial, const PathRecorder& reference, int k, double w) {
  const RecordedStep& step = reference.steps[k - 1];
  const State& previous = k == 1 ? initial : reference.steps[k - 2].state;
  switch (step.kind) {
    case ConstraintKind::kFixedLoad:
      return {&model, previous, StepConstraint::FixedLoad(previous.lambda + step.increment.dlambda),
              scales};
    case ConstraintKind::kHyperplane:
      return {&model, *step.switch_origin,
              StepConstraint::Hyperplane(step.plane_normal, 0.0, step.arc_length), scales};
    case ConstraintKind::kArcLength:
    case ConstraintKind::kDisplacement:
    // A step onto a kink ahead (kink_ahead.h) is replayed as the arc-length step of its length
    // along its own increment: the sphere meets the path at the kink.
    case ConstraintKind::kKink:
      break;
  }
  return {&model, previous, StepConstraint::ArcLength(step.arc_length, w), scales};
}

StartPoint ReplayedStart(const StepProblem& step, const PathRecorder& reference, int k,
                         StartKind kind) {
  StartPoint start;
  start.kind = kind;
  start.r = step.base.r;
  start.du = reference.steps[k - 1].prediction.du;
  start.dlambda = reference.steps[k - 1].prediction.dlambda;
  start.across_contact_change = reference.steps[k - 1].across_contact_change;
  return start;
}

bool ReplayedReversed(const PathRecorder& reference, int k, const StepPoint& answer, double w) {
  const RecordedStep& step = reference.steps[k - 1];
  const StepPoint& ref = step.increment;
  return step.kind != ConstraintKind::kFixedLoad &&
         HInner(answer.du, answer.dlambda, ref.du, ref.dlambda, w) <= 0.0;
}

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
    const StepProblem problem = ReplayedStep(model, scales, initial, reference, k, w);
    StartPoint start = ReplayedStart(problem, reference, k, options.start);
    // A step off a bifurcation point starts there, not where the previous step ended.
    if (problem.constraint.kind != ConstraintKind::kHyperplane) {
      start.warm_state = previous_warm_state;
    }

    StepAttempt attempt;
    attempt.step = k;
    attempt.kind = problem.constraint.kind;
    attempt.arc_length =
        attempt.kind == ConstraintKind::kFixedLoad ? 0.0 : problem.constraint.arc_length;
    RecordJudgedStep(SolveAndJudge(formulation, problem, start, options), &attempt);
    ++summary.attempts;
    // The reference direction decides "forward": the answer must not point against the
    // reference step (the other root of (33)).
    attempt.reversed = ReplayedReversed(reference, k, attempt.result.point, w);
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
