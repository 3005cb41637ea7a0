#include "path/path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "path/arc_length_norm.h"
#include "path/critical_points.h"
#include "path/kink_location.h"
#include "path/stability.h"
#include "path/step_solve.h"
#include "path/turn_back.h"

namespace cb {

bool PathOptions::IsValid(std::string* why) const {
  if (!(arc_length > 0.0) || !std::isfinite(arc_length)) {
    *why = "arc_length must be positive and finite";
    return false;
  }
  if (!(lambda_weight >= 0.0) || !std::isfinite(lambda_weight)) {
    *why = "lambda_weight must be >= 0 and finite";
    return false;
  }
  if (max_steps < 1) {
    *why = "max_steps must be >= 1";
    return false;
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    *why = "tolerance must be positive and finite";
    return false;
  }
  if (max_cutbacks < 0) {
    *why = "max_cutbacks must be >= 0";
    return false;
  }
  return true;
}

State ZeroState(const ContactModel& model) {
  return {Vec::Zero(model.num_dofs()), Vec::Zero(model.num_pairs()), 0.0};
}

bool TangentPredictor(const ContactModel& model, const ContactScales& scales, const State& state,
                      double theta, double lambda_weight, Vec* du, double* dlambda,
                      std::string* why) {
  const BorderedStiffness stiffness(model, scales, state);
  if (!stiffness.SolveDisplacement(model.load_pattern(), du)) {
    *why = "tangent predictor: " +
           (stiffness.ok() ? std::string("the tangent is not finite") : stiffness.message());
    return false;
  }
  const double norm = std::sqrt(du->squaredNorm() + lambda_weight * lambda_weight);
  *du *= theta / norm;
  *dlambda = theta / norm;
  return true;
}

const char* ToString(BifurcationMode mode) {
  switch (mode) {
    case BifurcationMode::kOff:
      return "off";
    case BifurcationMode::kDetect:
      return "detect";
    case BifurcationMode::kSwitch:
      return "switch";
  }
  return "?";
}

bool ParseBifurcationMode(const std::string& text, BifurcationMode* mode) {
  for (BifurcationMode m :
       {BifurcationMode::kOff, BifurcationMode::kDetect, BifurcationMode::kSwitch}) {
    if (text == ToString(m)) {
      *mode = m;
      return true;
    }
  }
  return false;
}

const char* ToString(CriticalPointRecord::Kind kind) {
  switch (kind) {
    case CriticalPointRecord::Kind::kLimit:
      return "limit";
    case CriticalPointRecord::Kind::kBifurcation:
      return "bifurcation";
    case CriticalPointRecord::Kind::kStabilityChange:
      return "stability_change";
  }
  return "?";
}

PathSummary TraceArcLengthPath(const ContactModel& model, const ContactScales& scales,
                               const State& initial, Formulation& formulation,
                               const PathOptions& options, PathObserver* observer) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("path options: " + why);
  PathSummary summary;
  summary.final_state = initial;
  State state = initial;
  const double nominal = options.arc_length;
  const double w = options.lambda_weight;
  const bool watch_stability = options.bifurcations != BifurcationMode::kOff;

  // The reference direction: the tangent predictor for the first step, then the previous
  // accepted increment.
  Increment heading;
  if (!TangentPredictor(model, scales, state, nominal, w, &heading.du, &heading.dlambda, &why)) {
    summary.status = Status::kFailed;
    summary.message = why;
    return summary;
  }
  double theta = nominal;
  std::any previous_warm_state;
  // Stability of the current state and the load increment that led to it (for limit points).
  int stability = watch_stability ? UnstableModes(model, scales, state) : -1;
  double last_dlambda = 0.0;
  int last_kinks = 0;
  int branch = 0;
  // Set when a bifurcation point was located: the next step leaves it along `switch_mode`.
  std::optional<CriticalPointRecord> pending_switch;

  for (int step = 1; step <= options.max_steps; ++step) {
    bool accepted = false;
    StepAttempt attempt;
    const bool switching = pending_switch.has_value();
    const State base = switching ? pending_switch->state : state;
    const int cutbacks = switching ? 2 * options.max_cutbacks + 1 : options.max_cutbacks;
    for (int cut = 0; cut <= cutbacks && !accepted; ++cut) {
      StepProblem problem{&model, base, StepConstraint::ArcLength(theta, w), scales};
      StartPoint start;
      start.kind = options.start;
      if (switching) {
        // Off the bifurcation point along the null vector, at constant load: the root of (33)
        // nearest to it is on the other branch (its tangent there is the null vector).
        // Both senses of the null vector are tried before theta is cut (a solver may be drawn
        // back to the branch already traced from one side and not from the other).
        start.du = pending_switch->mode * (cut % 2 == 0 ? theta : -theta);
        start.dlambda = 0.0;
      } else {
        // (38), (41): the previous increment, rescaled to this step's theta.
        const double scale = theta / HNorm(heading.du, heading.dlambda, w);
        start.du = heading.du * scale;
        start.dlambda = heading.dlambda * scale;
      }
      start.r = base.r;  // (40)
      start.warm_state = previous_warm_state;

      attempt = StepAttempt();
      attempt.step = step;
      attempt.attempt = cut;
      attempt.kind = ConstraintKind::kArcLength;
      attempt.arc_length = theta;
      attempt.branch = branch + (switching ? 1 : 0);
      attempt.branch_switch = switching;
      attempt.predicted_du = start.du;
      attempt.predicted_dlambda = start.dlambda;
      JudgedStep judged = SolveAndJudge(formulation, problem, start, options);
      ++summary.attempts;
      attempt.result = std::move(judged.result);
      attempt.verdict = judged.verdict;
      attempt.state = std::move(judged.state);
      attempt.n_contact = judged.n_contact;
      const StepPoint& point = attempt.result.point;
      if (switching) {
        // It must leave along the null vector, not return to the branch already traced.
        attempt.reversed = std::abs(pending_switch->mode.dot(point.du)) < 0.5 * theta;
      } else {
        attempt.reversed = TurnsBack(point, heading, step > 1, theta, w);
      }
      attempt.accepted = attempt.verdict.verified && !attempt.reversed;
      if (attempt.result.status == Status::kStoppedByCaller) {
        // An interrupted solve is not an accepted step, even when the point it stopped at
        // happens to pass the verdict: the path stops before the step (the records and the
        // summary's accepted_steps agree; tests/interrupt_test.cc).
        attempt.accepted = false;
        if (observer != nullptr) observer->OnAttempt(attempt);
        summary.status = Status::kStoppedByCaller;
        summary.message = "stopped by the caller at step " + std::to_string(step);
        return summary;
      }
      if (attempt.accepted) {
        accepted = true;
        break;
      }
      if (observer != nullptr) observer->OnAttempt(attempt);
      if (!switching || cut % 2 == 1) theta *= 0.5;
    }
    if (!accepted && switching) {
      // Every attempt returned to the branch already traced (or failed): say so, and go on
      // along that branch from the state accepted past the bifurcation point.
      CriticalPointRecord failed = *pending_switch;
      failed.switched = false;
      failed.message =
          "the branch switch failed: every attempt along the null vector " +
          std::string("returned to the branch already traced or failed the verdict; ") +
          "the path goes on along it";
      if (observer != nullptr) observer->OnCriticalPoint(failed);
      pending_switch.reset();
      if (watch_stability) stability = UnstableModes(model, scales, state);
      theta = nominal;
      --step;
      continue;
    }
    if (!accepted) {
      summary.status = Status::kFailed;
      summary.message = "step " + std::to_string(step) + " failed the verdict after " +
                        std::to_string(options.max_cutbacks) + " cut-backs of the arc length" +
                        (switching ? " (leaving the bifurcation point of step " +
                                         std::to_string(pending_switch->step) + ")"
                                   : std::string());
      return summary;
    }
    if (switching) {
      ++branch;
      ++summary.branch_switches;
      pending_switch.reset();
    }
    // The direction to continue in: the increment just taken, or, past a kink, the increment
    // from the kink (the path's direction on the branch it has turned onto). Without this a
    // step that cut across a corner would be continued back along the new branch.
    heading.du = attempt.result.point.du;
    heading.dlambda = attempt.result.point.dlambda;
    if (options.locate_kinks) {
      PathObserver no_observer;
      const KinksOfStep kinks =
          KinkLocator(model, scales, formulation, options)
              .Locate(step, base, attempt.state, observer != nullptr ? *observer : no_observer);
      attempt.kinks = kinks.found;
      summary.kinks += attempt.kinks;
      if (const std::optional<State>& kink = kinks.nearest) {
        const Vec du_after = attempt.state.u - kink->u;
        const double dl_after = attempt.state.lambda - kink->lambda;
        if (HNorm(du_after, dl_after, w) > 1e-3 * theta) {
          heading.du = du_after;
          heading.dlambda = dl_after;
        }
      }
    }
    // Critical points between `base` and the new state.
    std::vector<CriticalPointRecord> critical;
    if (watch_stability) {
      attempt.stability = UnstableModes(model, scales, attempt.state);
      StepOrigin origin{base, switching ? -1 : stability, std::nullopt};
      if (!switching && step > 1) origin.previous = {last_dlambda, last_kinks};
      const bool may_switch = options.bifurcations == BifurcationMode::kSwitch &&
                              summary.branch_switches < options.max_branch_switches;
      critical = CriticalPointFinder(model, scales, formulation, options)
                     .Find(origin, attempt, may_switch);
      for (const CriticalPointRecord& point : critical) {
        if (point.kind == CriticalPointRecord::Kind::kLimit) ++summary.limit_points;
        if (point.kind == CriticalPointRecord::Kind::kBifurcation) ++summary.bifurcations;
      }
    }
    if (observer != nullptr) observer->OnAttempt(attempt);
    for (const CriticalPointRecord& point : critical) {
      if (observer != nullptr) observer->OnCriticalPoint(point);
      if (point.switched) pending_switch = point;
    }
    previous_warm_state = attempt.result.warm_state;
    last_dlambda = attempt.result.point.dlambda;
    last_kinks = attempt.kinks;
    stability = attempt.stability;
    state = attempt.state;
    summary.final_state = state;
    ++summary.accepted_steps;
    theta = std::min(nominal, 2.0 * theta);
    if (pending_switch) {
      // The next step starts from the bifurcation point, not from the state just accepted
      // past it on the branch already traced.
      stability = UnstableModes(model, scales, pending_switch->state);
      previous_warm_state = std::any();
    }
    if (options.controls.interrupted && options.controls.interrupted()) {
      summary.status = Status::kStoppedByCaller;
      summary.message = "stopped by the caller after step " + std::to_string(step);
      return summary;
    }
  }
  summary.status = Status::kConverged;
  summary.message = std::to_string(summary.accepted_steps) + " steps accepted";
  return summary;
}

PathSummary SolveFixedLoad(const ContactModel& model, const ContactScales& scales,
                           const State& initial, double lambda, Formulation& formulation,
                           const PathOptions& options, PathObserver* observer, const State* guess) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("path options: " + why);
  StepProblem problem{&model, initial, StepConstraint::FixedLoad(lambda), scales};
  StartPoint start;
  start.kind = options.start;
  start.du = guess != nullptr ? Vec(guess->u - initial.u) : Vec(Vec::Zero(model.num_dofs()));
  start.dlambda = lambda - initial.lambda;
  start.r = guess != nullptr ? guess->r : initial.r;
  StepAttempt attempt;
  attempt.step = 1;
  attempt.kind = ConstraintKind::kFixedLoad;
  attempt.predicted_du = start.du;
  attempt.predicted_dlambda = start.dlambda;
  JudgedStep judged = SolveAndJudge(formulation, problem, start, options);
  attempt.result = std::move(judged.result);
  attempt.verdict = judged.verdict;
  attempt.accepted = attempt.verdict.verified;
  attempt.state = std::move(judged.state);
  attempt.n_contact = judged.n_contact;
  if (observer != nullptr) observer->OnAttempt(attempt);

  PathSummary summary;
  summary.attempts = 1;
  summary.final_state = attempt.accepted ? attempt.state : initial;
  summary.accepted_steps = attempt.accepted ? 1 : 0;
  if (attempt.accepted) {
    summary.status = Status::kConverged;
    summary.message = "fixed-load step verified";
  } else {
    summary.status = attempt.result.status == Status::kStoppedByCaller ? Status::kStoppedByCaller
                                                                       : Status::kFailed;
    summary.message =
        "fixed-load step not verified (solver: " + std::string(ToString(attempt.result.status)) +
        ", " + attempt.result.message + ")";
  }
  return summary;
}

}  // namespace cb
