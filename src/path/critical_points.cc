#include "path/critical_points.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "path/arc_length_norm.h"
#include "path/stability.h"
#include "path/step_solve.h"

namespace cb {
namespace {

// A limit point at the origin: the load parameter turned there, between the previous step on
// the branch and this one.
std::optional<CriticalPointRecord> LimitPoint(const StepOrigin& origin, const StepAttempt& taken) {
  if (!origin.previous || !(taken.result.point.dlambda * origin.previous->dlambda < 0.0)) {
    return std::nullopt;
  }
  CriticalPointRecord limit;
  limit.step = taken.step;
  limit.kind = CriticalPointRecord::Kind::kLimit;
  // A kink in one of the two steps around it: a limit point made by a contact change.
  limit.nonsmooth = taken.kinks + origin.previous->kinks > 0;
  limit.state = origin.state;
  limit.verdict.verified = true;  // an accepted state
  limit.message = "the load parameter turned at the accepted state before this step";
  return limit;
}

// The orientation of the path at a state, moving along (du, dlambda): the sign of the
// determinant of the step's Jacobian bordered by the arc-length row,
//   det [A  -f; du^T  w^2 dlambda] = det A (w^2 dlambda + du^T K^-1 f)   (K^-1: on Z),
// with sign det A = (-1)^(unstable modes). At a limit point both factors change sign; at a
// simple bifurcation point only det A does. So a change of the count with no change of the
// orientation is the limit point, and a change of the orientation is a bifurcation point (the
// classical test; it holds when the two are a hair apart, as they are on P2).
// The Schur factor w^2 dlambda + du^T K^-1 f of the bordered determinant at `at`; its sign is
// also the sign of the load component of the path's tangent (K^-1 f, 1) oriented along
// (du, dlambda). Empty when K cannot be factored.
std::optional<double> SchurFactor(const BorderedStiffness& stiffness, const ContactModel& model,
                                  const Vec& du, double dlambda, double w) {
  Vec tangent;
  if (stiffness.unstable_modes() < 0 ||
      !stiffness.SolveDisplacement(model.load_pattern(), &tangent)) {
    return std::nullopt;
  }
  return w * w * dlambda + du.dot(tangent);
}

int Sign(double x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

int Orientation(const ContactModel& model, const ContactScales& scales, const State& at,
                const Vec& du, double dlambda, double w) {
  const BorderedStiffness stiffness(model, scales, at);
  const std::optional<double> schur = SchurFactor(stiffness, model, du, dlambda, w);
  if (!schur) return 0;
  const int det_sign = stiffness.unstable_modes() % 2 == 0 ? 1 : -1;
  return det_sign * Sign(*schur);
}

// The direction the load moves in along the path at `at` (oriented along (du, dlambda)):
// +1, -1, or 0 when it cannot be told. It changes sign at a smooth limit point, where the
// tangent's load component passes through zero.
int LoadDirection(const ContactModel& model, const ContactScales& scales, const State& at,
                  const Vec& du, double dlambda, double w) {
  const BorderedStiffness stiffness(model, scales, at);
  const std::optional<double> schur = SchurFactor(stiffness, model, du, dlambda, w);
  return schur ? Sign(*schur) : 0;
}

// |psi^T f| / |f| for the null vector psi at `at`: zero at a bifurcation point, not at a limit
// point; 1 when it cannot be computed.
double LoadCosine(const ContactModel& model, const ContactScales& scales, const State& at) {
  const BorderedStiffness stiffness(model, scales, at);
  Mat basis;
  const Vec& f = model.load_pattern();
  if (!stiffness.NullSpace(1, 8, &basis) || !(f.norm() > 0.0)) return 1.0;
  return std::abs(basis.col(0).dot(f)) / f.norm();
}

// The bifurcation mode in a near-null space `basis` (d x k): the combination orthogonal to the
// load pattern f. At a simple bifurcation point phi^T f = 0 (f lies in the range of the bordered
// stiffness; docs/method.md section 5), while a limit mode has psi^T f != 0. On P2 the limit
// point B lies a hair from C, so the smallest two eigenvalues are both near zero there and a
// single inverse iteration returns a mix of psi and phi whose proportions are rounding's:
// the mode is taken from the two-dimensional near-null space instead, which rounding cannot mix.
// Empty when every vector of the space is orthogonal to f (no direction is singled out).
std::optional<Vec> ModeOrthogonalToLoad(const Mat& basis, const Vec& f) {
  const Vec loads = basis.transpose() * f;  // psi_i^T f
  if (basis.cols() == 1) return Vec(basis.col(0));
  if (!(loads.norm() > 1e-10 * f.norm())) return std::nullopt;
  // Of the space's vectors, those orthogonal to f; with k = 2 it is one direction.
  const Vec c = Eigen::Vector2d(-loads[1], loads[0]);
  return Vec(basis * c);
}

// The direction to leave a bifurcation point along: the bifurcation mode (ModeOrthogonalToLoad),
// made orthogonal to the chord of the traced path across the point (the plane off the point is
// then orthogonal to that branch: the branch switch's hyperplane, step_leg.h), and signed so
// that its largest component is positive (reproducible).
bool BranchDirection(const ContactModel& model, const ContactScales& scales, const State& at,
                     const Vec& chord_u, Vec* mode, std::string* why) {
  const BorderedStiffness stiffness(model, scales, at);
  Mat basis;
  if (!stiffness.NullSpace(2, 4, &basis)) {
    *why = "no null vector at the bifurcation point: " + stiffness.message();
    return false;
  }
  std::optional<Vec> phi = ModeOrthogonalToLoad(basis, model.load_pattern());
  if (!phi) {
    *why =
        "the near-null space at the bifurcation point is orthogonal to the load: no mode "
        "is singled out";
    return false;
  }
  *mode = std::move(*phi);
  const double cc = chord_u.squaredNorm();
  if (cc > 0.0) *mode -= (mode->dot(chord_u) / cc) * chord_u;
  const double norm = mode->norm();
  if (!(norm > 0.0)) {
    *why = "the null vector at the bifurcation point is the path's own direction";
    return false;
  }
  *mode /= norm;
  Eigen::Index largest = 0;
  mode->cwiseAbs().maxCoeff(&largest);
  if ((*mode)[largest] < 0.0) *mode = -*mode;
  return true;
}

}  // namespace

CriticalPointFinder::CriticalPointFinder(const ContactModel& model, const ContactScales& scales,
                                         Formulation& formulation, const PathOptions& options)
    : model_(model), scales_(scales), formulation_(formulation), options_(options) {}

std::vector<CriticalPointRecord> CriticalPointFinder::Find(const StepOrigin& origin,
                                                           const StepAttempt& taken,
                                                           bool may_switch) const {
  std::vector<CriticalPointRecord> critical;
  if (std::optional<CriticalPointRecord> limit = LimitPoint(origin, taken)) {
    if (limit->nonsmooth) {
      PlaceAtTheKink(origin, taken, &*limit);
    } else {
      LocateLimitPoint(origin, taken, &*limit);
    }
    critical.push_back(*limit);
  }
  if (origin.unstable_modes < 0 || taken.stability < 0 ||
      taken.stability == origin.unstable_modes) {
    return critical;
  }
  if (ContactStatusChanged(origin.state, taken)) {
    CriticalPointRecord point;
    point.step = taken.step;
    point.kind = CriticalPointRecord::Kind::kStabilityChange;
    point.nonsmooth = true;
    point.state = origin.state;
    point.verdict.verified = true;
    point.message = "the number of unstable modes changed with the contact status";
    critical.push_back(point);
  } else {
    LocateModeChanges(origin, taken, may_switch, &critical);
  }
  return critical;
}

bool CriticalPointFinder::ContactStatusChanged(const State& origin,
                                               const StepAttempt& taken) const {
  const std::vector<bool> before = ClosedPairs(scales_, GapsAt(model_, origin.u), origin.r);
  const std::vector<bool> after =
      ClosedPairs(scales_, GapsAt(model_, taken.state.u), taken.state.r);
  return before != after || taken.kinks > 0;
}

// Each change of the count along the step is located. Whether the path crossed another branch
// is told by the orientation at the step's two accepted states, where it is well conditioned
// (P2's B and C lie a hair apart, and between them the tangent K^-1 f is rounding's): it
// changes at a bifurcation point and not at a limit point. When it changed, the bifurcation
// point is the change whose null vector is nearest orthogonal to the load (phi^T f = 0 there,
// psi^T f != 0 at a limit point), or the change where the count moved by two at once (both
// within the bracket).
void CriticalPointFinder::LocateModeChanges(const StepOrigin& origin, const StepAttempt& taken,
                                            bool may_switch,
                                            std::vector<CriticalPointRecord>* critical) const {
  const double w = options_.lambda_weight;
  const Vec& chord_u = taken.result.point.du;
  const double chord_l = taken.result.point.dlambda;
  const int start = Orientation(model_, scales_, origin.state, chord_u, chord_l, w);
  const int end = Orientation(model_, scales_, taken.state, chord_u, chord_l, w);
  const bool crossed_a_branch = start != 0 && end != 0 && start != end;
  double t_from = 0.0;
  int modes = origin.unstable_modes;
  State from = origin.state;
  std::vector<CriticalPointRecord> changes;
  std::vector<double> load_cosines;
  for (int guard = 0; guard < 8 && modes != taken.stability; ++guard) {
    CriticalPointRecord point;
    point.step = taken.step;
    point.kind = CriticalPointRecord::Kind::kBifurcation;
    point.state = from;
    point.verdict.verified = true;
    const PastTheChange past =
        BracketModeChange(origin.state, modes, taken.state, taken.stability, t_from, &point);
    if (!point.located) {
      point.kind = CriticalPointRecord::Kind::kStabilityChange;
      critical->push_back(point);
      return;
    }
    const bool both = std::abs(past.modes - modes) >= 2;
    load_cosines.push_back(both ? -1.0 : LoadCosine(model_, scales_, point.state));
    changes.push_back(std::move(point));
    t_from = past.t;
    modes = past.modes;
    from = past.state;
  }
  if (!crossed_a_branch || changes.empty()) return;  // limit points only (LimitPoint)
  const auto nearest = std::min_element(load_cosines.begin(), load_cosines.end());
  CriticalPointRecord& point = changes[nearest - load_cosines.begin()];
  std::string why;
  if (!BranchDirection(model_, scales_, point.state, chord_u, &point.mode, &why)) {
    point.message = "located; " + why;
    critical->push_back(point);
    return;
  }
  point.message = "located";
  if (may_switch) {
    point.switched = true;
    point.message += "; the next step leaves it onto the other branch";
  }
  critical->push_back(point);
}

// Brackets, by bisection of the arc length from accepted state a towards b, the first point
// where the number of unstable modes changes from `modes_a` (b has `modes_b`); each trial is
// an arc-length step from a, predicted along the chord b - a and judged by the verdict.
// Searches t in (t_from, chord] and leaves in `point` the verified trial nearest the change on
// a's side (`point->state`, whose null vector is taken), the bisections and whether it was
// located (else `point->message` says why not).
CriticalPointFinder::PastTheChange CriticalPointFinder::BracketModeChange(
    const State& a, int modes_a, const State& b, int modes_b, double t_from,
    CriticalPointRecord* point) const {
  const double w = options_.lambda_weight;
  const Vec chord_u = b.u - a.u;
  const double chord_l = b.lambda - a.lambda;
  const double chord = HNorm(chord_u, chord_l, w);
  double lo = t_from;
  PastTheChange past{chord, modes_b, b};
  while (past.t - lo > options_.bifurcation_tolerance * chord && point->bisections < 60) {
    const double t = 0.5 * (lo + past.t);
    StepProblem problem{&model_, a, StepConstraint::ArcLength(t, w), scales_};
    StartPoint start;
    start.kind = StartKind::kWarm;
    start.du = chord_u * (t / chord);
    start.dlambda = chord_l * (t / chord);
    start.r = a.r + (t / chord) * (b.r - a.r);
    const JudgedStep trial = SolveAndJudge(formulation_, problem, start, options_);
    ++point->bisections;
    if (!trial.verdict.verified) {
      point->message = "a bisection step failed the verdict (" + trial.result.message + ")";
      return past;
    }
    const int modes = UnstableModes(model_, scales_, trial.state);
    if (modes < 0 && options_.controls.interrupted && options_.controls.interrupted()) {
      // The count was abandoned on the interrupt (stability.h): nothing is bracketed.
      point->message = "stopped by the caller while counting the unstable modes";
      return past;
    }
    if (modes == modes_a) {
      lo = t;
      point->state = trial.state;
      point->verdict = trial.verdict;
    } else {
      past = {t, modes, trial.state};
    }
  }
  point->located = true;
  return past;
}

// Locates a smooth limit point by bisection on the sign of the load component of the path's
// tangent (LoadDirection): at the origin the load still moves the way it did before the turn
// when the limit point lies ahead, within this step; else it lies behind, within the previous
// step, and the trials go back along the mirrored chord (-du, dlambda), the direction the path
// came from near a turn of the load. Each trial is an arc-length step (33) from the origin,
// judged by the verdict. The bracket is closed to limit_point_tolerance of the chord; the load
// being stationary there, lambda is then exact to its square. Leaves `limit` at the accepted
// state when the change cannot be bracketed.
void CriticalPointFinder::LocateLimitPoint(const StepOrigin& origin, const StepAttempt& taken,
                                           CriticalPointRecord* limit) const {
  const double w = options_.lambda_weight;
  const Vec& chord_u = taken.result.point.du;
  const double chord_l = taken.result.point.dlambda;
  const double chord = HNorm(chord_u, chord_l, w);
  const int before = Sign(origin.previous->dlambda);  // the load's direction before the turn
  const int at_origin = LoadDirection(model_, scales_, origin.state, chord_u, chord_l, w);
  if (at_origin == 0 || !(chord > 0.0)) return;
  const bool ahead = at_origin == before;
  const Vec direction_u = ahead ? Vec(chord_u) : Vec(-chord_u);
  auto trial_at = [&](double t) {
    StepProblem problem{&model_, origin.state, StepConstraint::ArcLength(t, w), scales_};
    StartPoint start;
    start.kind = StartKind::kWarm;
    start.du = direction_u * (t / chord);
    start.dlambda = chord_l * (t / chord);
    start.r = origin.state.r + (t / chord) * (taken.state.r - origin.state.r);
    ++limit->bisections;
    return SolveAndJudge(formulation_, problem, start, options_);
  };
  // The far end of the bracket: the accepted state ahead, a trial one chord back behind.
  State far = taken.state;
  if (!ahead) {
    const JudgedStep back = trial_at(chord);
    if (!SolvedAndVerified(back.result, back.verdict)) return;
    far = back.state;
  }
  if (LoadDirection(model_, scales_, far, chord_u, chord_l, w) != -at_origin) return;
  double lo = 0.0, hi = chord;
  State near_state = origin.state;
  Verdict near_verdict = limit->verdict;
  Verdict far_verdict = limit->verdict;
  while (hi - lo > kLimitPointTolerance * chord && limit->bisections < 80) {
    const double t = 0.5 * (lo + hi);
    const JudgedStep trial = trial_at(t);
    if (!SolvedAndVerified(trial.result, trial.verdict)) {
      limit->message +=
          "; not located: a bisection step failed the verdict (" + trial.result.message + ")";
      return;
    }
    if (LoadDirection(model_, scales_, trial.state, chord_u, chord_l, w) == at_origin) {
      lo = t;
      near_state = trial.state;
      near_verdict = trial.verdict;
    } else {
      hi = t;
      far = trial.state;
      far_verdict = trial.verdict;
    }
  }
  // Of the two ends, the one where the load went furthest in its direction before the turn.
  const bool near_wins = before * (near_state.lambda - far.lambda) >= 0.0;
  limit->state = near_wins ? near_state : far;
  limit->verdict = near_wins ? near_verdict : far_verdict;
  limit->located = true;
  limit->message = "located by bisection on the sign of the tangent's load component";
}

// A limit point made by a contact change is where the load turns at a kink: of the kinks
// located in the two steps around it, the one where the load went furthest in its direction
// before the turn. Left at the accepted state when neither step's kink is at hand.
void CriticalPointFinder::PlaceAtTheKink(const StepOrigin& origin, const StepAttempt& taken,
                                         CriticalPointRecord* limit) const {
  const int before = origin.previous->dlambda > 0.0 ? 1 : -1;
  const State* kink = nullptr;
  for (const std::optional<State>* candidate : {&origin.previous->kink, &taken.kink}) {
    if (!candidate->has_value()) continue;
    if (kink == nullptr || before * ((*candidate)->lambda - kink->lambda) > 0.0) {
      kink = &**candidate;
    }
  }
  if (kink == nullptr) return;
  limit->state = *kink;
  limit->located = true;  // the kink was located and verified (section 6)
  limit->message = "the load parameter turned at a kink";
}

}  // namespace cb
