#include "path/arc_length_tracer.h"

#include <algorithm>
#include <string>
#include <utility>

#include "path/corner_prediction.h"
#include "path/stability.h"
#include "path/step_solve.h"
#include "path/turn_back.h"

namespace cb {
namespace {

constexpr char kKinkNotLocated[] = "; not accepted: a kink within the step was not located";

}  // namespace

ArcLengthTracer::ArcLengthTracer(const ContactModel& model, const ContactScales& scales,
                                 Formulation& formulation, const PathOptions& options,
                                 PathObserver* observer)
    : model_(model),
      scales_(scales),
      formulation_(formulation),
      options_(options),
      observer_(observer != nullptr ? *observer : no_observer_),
      kink_locator_(model, scales, formulation, options),
      critical_point_finder_(model, scales, formulation, options),
      kink_ahead_finder_(model, scales, kink_locator_, options),
      stagnation_(options.stagnation, options.arc_length, options.lambda_weight) {
  options.Validate();
}

PathSummary ArcLengthTracer::Run(const State& initial) {
  if (!Start(initial)) return summary_;
  while (summary_.accepted_steps < options_.max_steps) {
    const int step = summary_.accepted_steps + 1;
    const std::unique_ptr<StepLeg> leg = NextLeg();
    StepAttempt attempt;
    LocatedKinks kinks;
    const Outcome outcome = AttemptWithCutbacks(step, *leg, &attempt, &kinks);
    if (outcome == Outcome::kStoppedByCaller) {
      return Finish(Status::kStoppedByCaller,
                    "stopped by the caller at step " + std::to_string(step));
    }
    if (outcome == Outcome::kRejected) {
      if (leg->switches_branch()) {
        AbandonBranchSwitch();  // not a failure of the path: it goes on along its branch
        continue;
      }
      if (StepOntoKinkAhead(step, *leg, attempt.attempt + 1)) continue;
      return Finish(Status::kFailed, StepFailure(step, attempt));
    }
    if (leg->switches_branch()) EnterNewBranch();
    RecordKinksAndRedirect(kinks, &attempt);
    const std::vector<CriticalPointRecord> critical = DetectCriticalPoints(*leg, &attempt);
    Accept(attempt, critical);
    if (auto why = stagnation_.Observe(step, attempt.arc_length,
                                       {attempt.result.point.du, attempt.result.point.dlambda})) {
      return Finish(Status::kFailed, *why);
    }
    if (InterruptedByCaller()) {
      return Finish(Status::kStoppedByCaller,
                    "stopped by the caller after step " + std::to_string(step));
    }
  }
  const std::string accepted = std::to_string(summary_.accepted_steps) + " steps accepted";
  if (summary_.kinks_not_located > 0) {
    return Finish(Status::kFailed, accepted + ", but " +
                                       std::to_string(summary_.kinks_not_located) +
                                       " kinks were not located (kinks.csv: verified, between)");
  }
  return Finish(Status::kConverged, accepted);
}

// The first heading is the tangent predictor at `initial`.
bool ArcLengthTracer::Start(const State& initial) {
  summary_ = PathSummary();
  kinks_stepped_onto_.clear();
  summary_.final_state = initial;
  stagnation_ = StagnationMonitor(options_.stagnation, options_.arc_length, options_.lambda_weight);
  at_ = Position();
  next_ = NextStep();
  at_.accepted.state = initial;
  std::string why;
  if (!TangentPredictor(model_, scales_, initial, options_.arc_length, options_.lambda_weight,
                        &at_.heading.du, &at_.heading.dlambda, &why)) {
    // An interrupt abandons the tangent's factorisation on a large body (stability.h).
    if (InterruptedByCaller()) {
      Finish(Status::kStoppedByCaller, "stopped by the caller before step 1 (" + why + ")");
    } else {
      Finish(Status::kFailed, why);
    }
    return false;
  }
  if (options_.bifurcations != BifurcationMode::kOff) {
    at_.accepted.unstable_modes = UnstableModes(model_, scales_, initial);
  }
  next_.theta = options_.arc_length;
  return true;
}

std::unique_ptr<StepLeg> ArcLengthTracer::NextLeg() const {
  if (next_.branch_switch) {
    return std::make_unique<BranchSwitchLeg>(*next_.branch_switch, at_.branch + 1);
  }
  // Before the first accepted step the heading is the tangent: no path to turn back onto.
  return std::make_unique<ContinuationLeg>(at_.accepted, at_.branch, at_.heading, Trail(),
                                           options_.lambda_weight);
}

// The turn-back guard's trail: x_k - heading (the state or kink the heading comes from; none
// on a kink stepped onto), then the accepted states behind, as increments from x_k. While those
// reach back to the path's first state, the trail goes on beyond it for twice the nominal theta
// along the first chord: the path through the first state goes on there too (to negative load from
// the unloaded state), and an answer beyond the start is as much a return as one onto the path
// traced (a cold-started Scholtes step of ipopt-mpcc on the small arch went there at theta 0.2,
// 0.4, 0.55 and 0.6, and the path went on in negative load, every step verified).
std::vector<Increment> ArcLengthTracer::Trail() const {
  if (summary_.accepted_steps == 0) return {};
  const State& x = at_.accepted.state;
  // On a kink stepped onto, the heading is the direction that leaves it, from no point behind.
  std::vector<Increment> trail;
  if (at_.on_kink < 0) trail.push_back({-at_.heading.du, -at_.heading.dlambda});
  for (const State& point : at_.behind) trail.push_back({point.u - x.u, point.lambda - x.lambda});
  if (at_.behind_reaches_start && !at_.behind.empty()) {
    const State& start = at_.behind.back();
    const State& next = at_.behind.size() > 1 ? at_.behind[at_.behind.size() - 2] : x;
    const double chord =
        HNorm(start.u - next.u, start.lambda - next.lambda, options_.lambda_weight);
    if (chord > 0.0) {
      const double beyond = 2.0 * options_.arc_length / chord;
      trail.push_back({start.u - x.u + (start.u - next.u) * beyond,
                       start.lambda - x.lambda + (start.lambda - next.lambda) * beyond});
    }
  }
  return trail;
}

// Keeps the state the step left from behind the path (none across a branch switch: the trail
// starts again at the bifurcation point, which the heading reaches), as far back as twice the
// nominal arc length, and at most kMaxBehind states.
void ArcLengthTracer::KeepBehind(const StepAttempt& attempt) {
  constexpr std::size_t kMaxBehind = 32;
  if (attempt.branch_switch) {
    at_.behind.clear();
    at_.behind_reaches_start = false;
    return;
  }
  at_.behind.push_front(at_.accepted.state);
  const double w = options_.lambda_weight;
  double length =
      HNorm(attempt.state.u - at_.behind[0].u, attempt.state.lambda - at_.behind[0].lambda, w);
  std::size_t keep = 1;
  while (keep < at_.behind.size() && keep < kMaxBehind && length < 2.0 * options_.arc_length) {
    const State& a = at_.behind[keep - 1];
    const State& b = at_.behind[keep];
    length += HNorm(a.u - b.u, a.lambda - b.lambda, w);
    ++keep;
  }
  at_.behind_reaches_start = at_.behind_reaches_start && keep == at_.behind.size();
  at_.behind.resize(keep);
}

// Reports every rejected attempt, in attempt order, once the step is decided; the accepted one
// is reported by Accept, after its kinks. A verified attempt within which a kink cannot be
// located is cut back too (a shorter step brackets the kink more closely, and on P2's branch D
// at theta 0.5 that locates it); when no cut-back is accepted, the first such attempt is taken
// with its kink recorded as not located, and the path then ends as failed once its steps are
// done.
ArcLengthTracer::Outcome ArcLengthTracer::AttemptWithCutbacks(int step, const StepLeg& leg,
                                                              StepAttempt* attempt,
                                                              LocatedKinks* kinks) {
  const int per_theta = leg.predictions_per_arc_length();
  const int attempts = per_theta * (options_.max_cutbacks + 1);
  std::vector<StepAttempt> rejected;
  std::optional<StepAttempt> unlocated;  // the first verified attempt with a kink not located
  LocatedKinks unlocated_kinks;
  for (int index = 0; index < attempts; ++index) {
    *attempt = Attempt(step, index, leg);
    if (attempt->result.status == Status::kStoppedByCaller) {
      // An interrupted solve is not an accepted step, even when the point it stopped at
      // happens to pass the verdict: the path stops before the step (the records and the
      // summary's accepted_steps agree; tests/interrupt_test.cc).
      attempt->accepted = false;
      rejected.push_back(*attempt);
      ReportRejected(std::move(rejected), std::move(unlocated));
      return Outcome::kStoppedByCaller;
    }
    if (attempt->accepted) {
      LocatedKinks located = LocateKinks(leg, *attempt);
      if (located.of_step.not_located == 0) {
        *kinks = std::move(located);
        ReportRejected(std::move(rejected), std::move(unlocated));
        return Outcome::kAccepted;
      }
      attempt->accepted = false;
      if (!unlocated) {
        unlocated = *attempt;
        unlocated_kinks = std::move(located);
        if ((index + 1) % per_theta == 0) next_.theta *= 0.5;
        continue;
      }
      attempt->result.message += kKinkNotLocated;
    }
    rejected.push_back(*attempt);
    if ((index + 1) % per_theta == 0) next_.theta *= 0.5;
  }
  if (unlocated) {
    *attempt = std::move(*unlocated);
    attempt->accepted = true;
    *kinks = std::move(unlocated_kinks);
    next_.theta = attempt->arc_length;
    ReportRejected(std::move(rejected), std::nullopt);
    return Outcome::kAccepted;
  }
  ReportRejected(std::move(rejected), std::nullopt);
  return Outcome::kRejected;
}

// The rejected attempts of a step, with the attempt held back for its kink not located when a
// later one was taken, in attempt order.
void ArcLengthTracer::ReportRejected(std::vector<StepAttempt> rejected,
                                     std::optional<StepAttempt> held) {
  if (held) {
    held->result.message += kKinkNotLocated;
    rejected.push_back(std::move(*held));
  }
  std::stable_sort(
      rejected.begin(), rejected.end(),
      [](const StepAttempt& a, const StepAttempt& b) { return a.attempt < b.attempt; });
  for (const StepAttempt& a : rejected) observer_.OnAttempt(a);
}

StepAttempt ArcLengthTracer::Attempt(int step, int index, const StepLeg& leg) {
  const State& base = leg.origin().state;
  const double theta = next_.theta;
  StepProblem problem{&model_, base, leg.Constraint(index, theta, options_.lambda_weight), scales_};
  StartPoint start;
  start.kind = options_.start;
  Increment prediction = leg.Predict(index, theta);
  if (std::optional<Increment> bent = BentAtContactChange(leg, prediction)) {
    prediction = std::move(*bent);
    start.across_contact_change = true;
  }
  start.du = std::move(prediction.du);
  start.dlambda = prediction.dlambda;
  start.r = base.r;  // (40)
  start.warm_state = next_.warm_state;

  StepAttempt attempt;
  attempt.step = step;
  attempt.attempt = index;
  attempt.kind = problem.constraint.kind;
  attempt.arc_length = theta;
  attempt.branch = leg.branch();
  attempt.branch_switch = leg.switches_branch();
  if (attempt.kind == ConstraintKind::kHyperplane) {
    attempt.switch_origin = base;
    attempt.plane_normal = problem.constraint.normal;
  }
  attempt.predicted_du = start.du;
  attempt.predicted_dlambda = start.dlambda;
  attempt.across_contact_change = start.across_contact_change;
  RecordJudgedStep(SolveAndJudge(formulation_, problem, start, options_), &attempt);
  ++summary_.attempts;
  attempt.reversed = leg.Reversed(attempt.result.point, theta);
  attempt.accepted = SolvedAndVerified(attempt.result, attempt.verdict) && !attempt.reversed;
  return attempt;
}

// The corner prediction (corner_prediction.h) of a step along the branch, when kinks are
// located and the path has a state behind it to extrapolate the switching functions from.
std::optional<Increment> ArcLengthTracer::BentAtContactChange(const StepLeg& leg,
                                                              const Increment& prediction) const {
  if (leg.switches_branch() || !options_.locate_kinks || at_.behind.empty()) return std::nullopt;
  return CornerPrediction(model_, scales_, at_.behind.front(), leg.origin().state, prediction,
                          options_.lambda_weight);
}

// Every attempt on the planes off the bifurcation point failed the verdict: say so, and go on along
// that branch from the state accepted past the bifurcation point, at the nominal arc length (and,
// as the switch, without a backend state to reuse).
void ArcLengthTracer::AbandonBranchSwitch() {
  CriticalPointRecord failed = std::move(*next_.branch_switch);
  next_.branch_switch.reset();
  failed.switched = false;
  failed.message =
      "the branch switch failed: every attempt on the planes orthogonal to the null vector "
      "failed the verdict; the path goes on along its branch";
  observer_.OnCriticalPoint(failed);
  next_.theta = options_.arc_length;
}

// Every attempt of the step failed: if a contact change lies within twice theta ahead, the kink
// itself is taken as the step (closed by (53), judged by the verdict, recorded as a kink), and
// the path leaves it along the other piece (kink_ahead.h) at the nominal arc length, without a
// backend state to reuse (the kink's is of another system).
bool ArcLengthTracer::StepOntoKinkAhead(int step, const StepLeg& leg, int attempts) {
  if (!options_.locate_kinks || at_.behind.empty()) return false;
  std::optional<KinkAhead> ahead = kink_ahead_finder_.Find(
      step, at_.behind.front(), at_.accepted.state, at_.heading, 2.0 * options_.arc_length);
  if (!ahead) return false;
  const State& from = at_.accepted.state;
  // A kink stepped onto before: the path is going round between kinks, not on.
  for (const auto& [pair, state] : kinks_stepped_onto_) {
    if (pair == ahead->kink.pair &&
        HNorm(state.u - ahead->kink.state.u, state.lambda - ahead->kink.state.lambda,
              options_.lambda_weight) <= 1e-6 * options_.arc_length) {
      return false;
    }
  }
  // Leaving the kink must not go back onto the path traced (the piece it arrived on).
  const Increment arrived{ahead->kink.state.u - from.u, ahead->kink.state.lambda - from.lambda};
  std::vector<Increment> behind_kink{{-arrived.du, -arrived.dlambda}};
  for (const State& b : at_.behind) {
    behind_kink.push_back({b.u - ahead->kink.state.u, b.lambda - ahead->kink.state.lambda});
  }
  StepPoint leaving;
  leaving.du = ahead->leave.du * options_.arc_length;
  leaving.dlambda = ahead->leave.dlambda * options_.arc_length;
  if (TurnsBack(leaving, arrived, behind_kink, options_.arc_length, options_.lambda_weight)) {
    return false;
  }
  StepAttempt attempt;
  attempt.step = step;
  attempt.attempt = attempts;
  attempt.kind = ConstraintKind::kKink;
  attempt.branch = at_.branch;
  const StepProblem kink_step{&model_, from, StepConstraint::Kink(ahead->kink.pair), scales_};
  const int n_contact =
      CountContacts(kink_step, ahead->kink.result.point.g, ahead->kink.result.point.r);
  RecordJudgedStep({ahead->kink.result, ahead->kink.verdict, ahead->kink.state, n_contact},
                   &attempt);
  attempt.result.point.du = attempt.state.u - from.u;
  attempt.result.point.dlambda = attempt.state.lambda - from.lambda;
  attempt.arc_length =
      HNorm(attempt.result.point.du, attempt.result.point.dlambda, options_.lambda_weight);
  // The path's own predictor of that length (what a replay of the step starts from).
  const double scale =
      attempt.arc_length / HNorm(at_.heading.du, at_.heading.dlambda, options_.lambda_weight);
  attempt.predicted_du = at_.heading.du * scale;
  attempt.predicted_dlambda = at_.heading.dlambda * scale;
  attempt.accepted = true;
  attempt.kinks = 1;
  attempt.kink = attempt.state;
  observer_.OnKink(ahead->kink);
  ++summary_.kinks;
  ++summary_.attempts;
  const std::vector<CriticalPointRecord> critical = DetectCriticalPoints(leg, &attempt);
  Accept(attempt, critical);
  at_.heading = {ahead->leave.du * options_.arc_length, ahead->leave.dlambda * options_.arc_length};
  at_.on_kink = ahead->kink.pair;
  kinks_stepped_onto_.emplace_back(ahead->kink.pair, ahead->kink.state);
  next_.theta = options_.arc_length;
  next_.warm_state.reset();
  return true;
}

void ArcLengthTracer::EnterNewBranch() {
  ++at_.branch;
  ++summary_.branch_switches;
  next_.branch_switch.reset();
}

ArcLengthTracer::LocatedKinks ArcLengthTracer::LocateKinks(const StepLeg& leg,
                                                           const StepAttempt& attempt) const {
  LocatedKinks kinks;
  if (options_.locate_kinks) {
    kinks.of_step = kink_locator_.Locate(attempt.step, leg.origin().state, attempt.state, kinks,
                                         leg.switches_branch() ? -1 : at_.on_kink);
  }
  return kinks;
}

// The direction to continue in: the increment just taken, or, past a kink, the increment from
// the kink (the path's direction on the branch it has turned onto). Without this a step that
// cut across a corner would be continued back along the new branch.
void ArcLengthTracer::RecordKinksAndRedirect(const LocatedKinks& kinks, StepAttempt* attempt) {
  at_.heading = {attempt->result.point.du, attempt->result.point.dlambda};
  for (const KinkRecord& kink : kinks.records) observer_.OnKink(kink);
  attempt->kinks = kinks.of_step.found;
  summary_.kinks += attempt->kinks;
  summary_.kinks_not_located += kinks.of_step.not_located;
  attempt->kink = kinks.of_step.nearest;
  if (!attempt->kink) return;
  const Vec du_after = attempt->state.u - attempt->kink->u;
  const double dl_after = attempt->state.lambda - attempt->kink->lambda;
  if (HNorm(du_after, dl_after, options_.lambda_weight) > 1e-3 * attempt->arc_length) {
    at_.heading = {du_after, dl_after};
  }
}

// Counts the unstable modes at the new state, when they are watched, and finds the critical
// points between the step's origin and it.
std::vector<CriticalPointRecord> ArcLengthTracer::DetectCriticalPoints(const StepLeg& leg,
                                                                       StepAttempt* attempt) {
  if (options_.bifurcations == BifurcationMode::kOff) return {};
  attempt->stability = UnstableModes(model_, scales_, attempt->state);
  const bool may_switch = options_.bifurcations == BifurcationMode::kSwitch &&
                          summary_.branch_switches < options_.max_branch_switches;
  std::vector<CriticalPointRecord> critical =
      critical_point_finder_.Find(leg.origin(), *attempt, may_switch);
  for (const CriticalPointRecord& point : critical) {
    if (point.kind == CriticalPointRecord::Kind::kLimit) ++summary_.limit_points;
    if (point.kind == CriticalPointRecord::Kind::kBifurcation) ++summary_.bifurcations;
  }
  return critical;
}

void ArcLengthTracer::Accept(const StepAttempt& attempt,
                             const std::vector<CriticalPointRecord>& critical) {
  observer_.OnAttempt(attempt);
  KeepBehind(attempt);
  for (const CriticalPointRecord& point : critical) {
    observer_.OnCriticalPoint(point);
    if (point.switched) next_.branch_switch = point;
  }
  at_.accepted = {
      attempt.state, attempt.stability,
      StepOrigin::PreviousStep{attempt.result.point.dlambda, attempt.kinks, attempt.kink}};
  summary_.final_state = attempt.state;
  at_.on_kink = -1;
  ++summary_.accepted_steps;
  next_.theta = std::min(options_.arc_length, 2.0 * next_.theta);
  // A step leaving a bifurcation point starts there, not where this solve ended: this solve's
  // backend state is no start for it.
  next_.warm_state = next_.branch_switch ? std::any() : attempt.result.warm_state;
}

// Why the step failed: the verdict, or the time limit when the last cut-back ran into it.
std::string ArcLengthTracer::StepFailure(int step, const StepAttempt& last) const {
  const std::string after =
      " after " + std::to_string(options_.max_cutbacks) + " cut-backs of the arc length";
  if (last.result.status == Status::kTimeLimit) {
    return "step " + std::to_string(step) + " ran into the time limit" + after + " (" +
           last.result.message + ")";
  }
  return "step " + std::to_string(step) + " failed the verdict" + after;
}

bool ArcLengthTracer::InterruptedByCaller() const {
  return options_.controls.interrupted && options_.controls.interrupted();
}

PathSummary ArcLengthTracer::Finish(Status status, std::string message) {
  summary_.status = status;
  summary_.message = std::move(message);
  return summary_;
}

}  // namespace cb
