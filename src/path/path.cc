#include "path/path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "path/arc_length_norm.h"
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

namespace {

int UnstableModes(const ContactModel& model, const ContactScales& scales, const State& state) {
  return BorderedStiffness(model, scales, state, BorderedStiffness::Use::kModes).unstable_modes();
}

// Brackets, by bisection of the arc length from accepted state a towards b, the first point
// where the number of unstable modes changes from `modes_a`; each trial is an arc-length step
// from a, predicted along the chord b - a and judged by the verdict. Searches t in
// (t_from, chord] and leaves in `point` the verified trial nearest the change on a's side
// (`point->state`, whose null vector is taken), and in *t_change and *past the first verified
// point past it.
void LocateModeChange(const ContactModel& model, const ContactScales& scales, const State& a,
                      int modes_a, const State& b, double t_from, Formulation& formulation,
                      const PathOptions& options, CriticalPointRecord* point, double* t_change,
                      int* modes_after, State* past) {
  const double w = options.lambda_weight;
  const Vec chord_u = b.u - a.u;
  const double chord_l = b.lambda - a.lambda;
  const double chord = HNorm(chord_u, chord_l, w);
  double lo = t_from;
  double hi = chord;
  *modes_after = UnstableModes(model, scales, b);
  *past = b;
  while (hi - lo > options.bifurcation_tolerance * chord && point->bisections < 60) {
    const double t = 0.5 * (lo + hi);
    StepProblem problem{&model, a, StepConstraint::ArcLength(t, w), scales};
    StartPoint start;
    start.kind = StartKind::kWarm;
    start.du = chord_u * (t / chord);
    start.dlambda = chord_l * (t / chord);
    start.r = a.r + (t / chord) * (b.r - a.r);
    const JudgedStep trial = SolveAndJudge(formulation, problem, start, options);
    ++point->bisections;
    if (!trial.verdict.verified) {
      point->message = "a bisection step failed the verdict (" + trial.result.message + ")";
      *t_change = hi;
      return;
    }
    const int modes = UnstableModes(model, scales, trial.state);
    if (modes == modes_a) {
      lo = t;
      point->state = trial.state;
      point->verdict = trial.verdict;
    } else {
      hi = t;
      *modes_after = modes;
      *past = trial.state;
    }
  }
  *t_change = hi;
  point->located = true;
}

// The orientation of the path at a state, moving along (du, dlambda): the sign of the
// determinant of the step's Jacobian bordered by the arc-length row,
//   det [A  -f; du^T  w^2 dlambda] = det A (w^2 dlambda + du^T K^-1 f)   (K^-1: on Z),
// with sign det A = (-1)^(unstable modes). At a limit point both factors change sign; at a
// simple bifurcation point only det A does. So a change of the count with no change of the
// orientation is the limit point, and a change of the orientation is a bifurcation point (the
// classical test; it holds when the two are a hair apart, as they are on P2).
int Orientation(const ContactModel& model, const ContactScales& scales, const State& at,
                const Vec& du, double dlambda, double w) {
  const BorderedStiffness stiffness(model, scales, at);
  Vec tangent;
  if (stiffness.unstable_modes() < 0 ||
      !stiffness.SolveDisplacement(model.load_pattern(), &tangent)) {
    return 0;
  }
  const double schur = w * w * dlambda + du.dot(tangent);
  const int det_sign = stiffness.unstable_modes() % 2 == 0 ? 1 : -1;
  return schur > 0.0 ? det_sign : (schur < 0.0 ? -det_sign : 0);
}

// The direction to leave a bifurcation point along: the null vector there, made orthogonal to
// the tangent K^-1 f (a limit mode close by, as on P2, dominates the tangent) and signed so
// that its largest component is positive (reproducible).
bool BranchDirection(const ContactModel& model, const ContactScales& scales, const State& at,
                     Vec* mode, std::string* why) {
  const BorderedStiffness stiffness(model, scales, at);
  Mat basis;
  Vec tangent;
  if (!stiffness.NullSpace(1, 4, &basis) ||
      !stiffness.SolveDisplacement(model.load_pattern(), &tangent)) {
    *why = "no null vector at the bifurcation point: " + stiffness.message();
    return false;
  }
  *mode = basis.col(0);
  const double tt = tangent.squaredNorm();
  if (tt > 0.0) *mode -= (mode->dot(tangent) / tt) * tangent;
  const double norm = mode->norm();
  if (!(norm > 0.0)) {
    *why = "the null vector at the bifurcation point is the path's own tangent";
    return false;
  }
  *mode /= norm;
  Eigen::Index largest = 0;
  mode->cwiseAbs().maxCoeff(&largest);
  if ((*mode)[largest] < 0.0) *mode = -*mode;
  return true;
}

}  // namespace

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
      const double dlambda = attempt.result.point.dlambda;
      if (!switching && step > 1 && dlambda * last_dlambda < 0.0) {
        CriticalPointRecord limit;
        limit.step = step;
        limit.kind = CriticalPointRecord::Kind::kLimit;
        limit.nonsmooth = attempt.kinks + last_kinks > 0;
        limit.state = base;
        limit.verdict.verified = true;  // an accepted state
        limit.message = "the load parameter turned at the accepted state before this step";
        critical.push_back(limit);
        ++summary.limit_points;
      }
      if (!switching && stability >= 0 && attempt.stability >= 0 &&
          attempt.stability != stability) {
        const std::vector<bool> before = ClosedPairs(scales, GapsAt(model, base.u), base.r);
        const std::vector<bool> after =
            ClosedPairs(scales, GapsAt(model, attempt.state.u), attempt.state.r);
        if (before != after || attempt.kinks > 0) {
          CriticalPointRecord point;
          point.step = step;
          point.kind = CriticalPointRecord::Kind::kStabilityChange;
          point.nonsmooth = true;
          point.state = base;
          point.verdict.verified = true;
          point.message = "the number of unstable modes changed with the contact status";
          critical.push_back(point);
        } else {
          // Each change of the count along the step is located; where the orientation changes
          // across it, it is a bifurcation point (else the limit point, recorded above).
          const Vec& chord_u = attempt.result.point.du;
          const double chord_l = attempt.result.point.dlambda;
          double t_from = 0.0;
          int modes = stability;
          State from = base;
          for (int guard = 0; guard < 8 && modes != attempt.stability; ++guard) {
            CriticalPointRecord point;
            point.step = step;
            point.kind = CriticalPointRecord::Kind::kBifurcation;
            point.state = from;
            point.verdict.verified = true;
            double t_change = 0.0;
            int modes_after = attempt.stability;
            State past;
            LocateModeChange(model, scales, base, modes, attempt.state, t_from, formulation,
                             options, &point, &t_change, &modes_after, &past);
            if (!point.located) {
              point.kind = CriticalPointRecord::Kind::kStabilityChange;
              critical.push_back(point);
              break;
            }
            const int before = Orientation(model, scales, point.state, chord_u, chord_l, w);
            const int after = Orientation(model, scales, past, chord_u, chord_l, w);
            t_from = t_change;
            modes = modes_after;
            from = past;
            if (before == after) continue;  // the limit point
            ++summary.bifurcations;
            if (!BranchDirection(model, scales, point.state, &point.mode, &why)) {
              point.message = "located; " + why;
              critical.push_back(point);
              continue;
            }
            point.message = "located";
            if (options.bifurcations == BifurcationMode::kSwitch &&
                summary.branch_switches < options.max_branch_switches && !pending_switch &&
                std::none_of(critical.begin(), critical.end(),
                             [](const CriticalPointRecord& c) { return c.switched; })) {
              point.switched = true;  // the next step leaves along point.mode
              point.message += "; the next step leaves along the null vector";
            }
            critical.push_back(point);
          }
        }
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
