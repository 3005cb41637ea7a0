#include "path/path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "solvers/linear_solver.h"

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

namespace {

// g = -phi(u).
Vec GapsAt(const ContactModel& model, const Vec& u) {
  Vec phi;
  model.Gaps(u, &phi);
  return -phi;
}

// Contact status of each pair: closed when the min of (g/L, -r/R) picks the gap.
std::vector<bool> Closed(const ContactScales& scales, const Vec& g, const Vec& r) {
  std::vector<bool> closed(g.size());
  for (int p = 0; p < g.size(); ++p) closed[p] = g[p] / scales.length + r[p] / scales.force < 0.0;
  return closed;
}

double HInner(const Vec& a, double la, const Vec& b, double lb, double w) {
  return a.dot(b) + w * w * la * lb;
}

// H-distance from the point x_k + (du, dl) to the segment from x_{k-1} = x_k - (pu, pl) to x_k.
double DistanceToPreviousSegment(const Vec& du, double dl, const Vec& pu, double pl, double w) {
  const double pp = HInner(pu, pl, pu, pl, w);
  // Parameter s of the closest point x_k - s (pu, pl), s in [0, 1].
  const double s = pp > 0.0 ? std::clamp(-HInner(du, dl, pu, pl, w) / pp, 0.0, 1.0) : 0.0;
  const Vec eu = du + s * pu;
  const double el = dl + s * pl;
  return std::sqrt(HInner(eu, el, eu, el, w));
}

// The guard against turning back (issue: "the path does not turn back on itself"). The other
// root of (33) lies on the segment just traced (exactly at x_{k-1} when theta is unchanged),
// so an answer is rejected when it points backwards AND lies within 5% of theta of that
// segment. The inner product alone is not enough: at a kink the path may turn by more than
// 90 degrees, and the correct root then also points backwards, but away from the segment.
// On the first step there is no segment; the answer must not point against the tangent.
bool TurnsBack(const StepPoint& point, const Vec& previous_du, double previous_dlambda,
               bool have_segment, double theta, double w) {
  if (HInner(point.du, point.dlambda, previous_du, previous_dlambda, w) > 0.0) return false;
  if (!have_segment) return true;
  return DistanceToPreviousSegment(point.du, point.dlambda, previous_du, previous_dlambda, w) <=
         0.05 * theta;
}

}  // namespace

bool TangentPredictor(const ContactModel& model, const ContactScales& scales, const State& state,
                      double theta, double lambda_weight, Vec* du, double* dlambda,
                      std::string* why) {
  const int d = model.num_dofs();
  SpMat stiffness, curvature, gap_jacobian;
  model.Stiffness(state.u, &stiffness);
  model.GapCurvature(state.u, state.r, &curvature);
  model.GapJacobian(state.u, &gap_jacobian);
  const std::vector<bool> closed = Closed(scales, GapsAt(model, state.u), state.r);
  std::vector<int> closed_pairs;
  for (int p = 0; p < model.num_pairs(); ++p) {
    if (closed[p]) closed_pairs.push_back(p);
  }
  const int m = static_cast<int>(closed_pairs.size());
  std::vector<Triplet> t;
  t.reserve(stiffness.nonZeros() + curvature.nonZeros() + 2 * gap_jacobian.nonZeros());
  for (int j = 0; j < d; ++j) {
    for (SpMat::InnerIterator it(stiffness, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  }
  for (int j = 0; j < curvature.outerSize(); ++j) {
    for (SpMat::InnerIterator it(curvature, j); it; ++it) t.emplace_back(it.row(), j, -it.value());
  }
  // Row index of each closed pair in the bordered system.
  std::vector<int> border(model.num_pairs(), -1);
  for (int k = 0; k < m; ++k) border[closed_pairs[k]] = d + k;
  for (int j = 0; j < gap_jacobian.outerSize(); ++j) {
    for (SpMat::InnerIterator it(gap_jacobian, j); it; ++it) {
      const int row = border[it.row()];
      if (row < 0) continue;
      t.emplace_back(row, j, it.value());   // G_c
      t.emplace_back(j, row, -it.value());  // -G_c^T
    }
  }
  SpMat bordered(d + m, d + m);
  bordered.setFromTriplets(t.begin(), t.end());
  bordered.makeCompressed();
  Vec rhs = Vec::Zero(d + m);
  rhs.head(d) = model.load_pattern();
  auto solver = MakeLinearSolver(LinearSolverNames().front());
  Vec solution;
  if (!solver->Factorize(bordered) || !solver->Solve(rhs, &solution) || !solution.allFinite()) {
    *why = "tangent predictor: the stiffness bordered by the closed contacts is singular (" +
           solver->message() + ")";
    return false;
  }
  *du = solution.head(d);
  const double norm = std::sqrt(du->squaredNorm() + lambda_weight * lambda_weight);
  *du *= theta / norm;
  *dlambda = theta / norm;
  return true;
}

namespace {

// Locates the kink of every pair whose status changed between accepted states a and b
// (METHOD.md section 6), reporting each. Returns the verified kink nearest to b, if any.
std::optional<State> LocateKinks(const ContactModel& model, const ContactScales& scales,
                                 const State& a, const State& b, int step, Formulation& formulation,
                                 const PathOptions& options, PathObserver* observer, int* found) {
  const Vec ga = GapsAt(model, a.u);
  const Vec gb = GapsAt(model, b.u);
  const std::vector<bool> ca = Closed(scales, ga, a.r);
  const std::vector<bool> cb = Closed(scales, gb, b.r);
  const Vec du_step = b.u - a.u;
  const double dl_step = b.lambda - a.lambda;
  const double w = options.lambda_weight;
  const double chord = std::sqrt(HInner(du_step, dl_step, du_step, dl_step, w));
  std::optional<State> nearest;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (int p = 0; p < model.num_pairs(); ++p) {
    if (ca[p] == cb[p]) continue;
    // Switching function s = g/L + r/R changes sign at the kink; interpolate it linearly.
    const double sa = ga[p] / scales.length + a.r[p] / scales.force;
    const double sb = gb[p] / scales.length + b.r[p] / scales.force;
    const double t = std::clamp(sa / (sa - sb), 0.0, 1.0);
    StepProblem kink_step{&model, a, StepConstraint::Kink(p), scales};
    StartPoint start;
    start.kind = StartKind::kWarm;
    start.du = t * du_step;
    start.dlambda = t * dl_step;
    start.r = a.r + t * (b.r - a.r);
    KinkRecord record;
    record.step = step;
    record.pair = p;
    record.result = formulation.Solve(kink_step, start, options.controls);
    record.verdict = Judge(kink_step, record.result.point, options.tolerance);
    const Vec& du = record.result.point.du;
    const double dl = record.result.point.dlambda;
    record.state = {a.u + du, record.result.point.r, a.lambda + dl};
    // On the path between the two states: within two chords of each. (A step may cut across a
    // corner of the path, so the kink need not lie inside the chord's ball.)
    const Vec to_b = b.u - record.state.u;
    const double dl_to_b = b.lambda - record.state.lambda;
    const double from_a = std::sqrt(HInner(du, dl, du, dl, w));
    const double to_b_norm = std::sqrt(HInner(to_b, dl_to_b, to_b, dl_to_b, w));
    record.between = from_a <= 2.0 * chord && to_b_norm <= 2.0 * chord;
    if (record.verdict.verified && record.between) {
      ++*found;
      if (to_b_norm < nearest_distance) {
        nearest_distance = to_b_norm;
        nearest = record.state;
      }
    }
    if (observer != nullptr) observer->OnKink(record);
  }
  return nearest;
}

}  // namespace

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

  // The reference direction: the tangent predictor for the first step, then the previous
  // accepted increment.
  Vec previous_du;
  double previous_dlambda = 0.0;
  if (!TangentPredictor(model, scales, state, nominal, w, &previous_du, &previous_dlambda, &why)) {
    summary.status = Status::kFailed;
    summary.message = why;
    return summary;
  }
  double theta = nominal;
  std::any previous_backend;

  for (int step = 1; step <= options.max_steps; ++step) {
    bool accepted = false;
    StepAttempt attempt;
    for (int cut = 0; cut <= options.max_cutbacks && !accepted; ++cut) {
      StepProblem problem{&model, state, StepConstraint::ArcLength(theta, w), scales};
      StartPoint start;
      start.kind = options.start;
      // (38), (41): the previous increment, rescaled to this step's theta.
      const double scale = theta / std::sqrt(HInner(previous_du, previous_dlambda, previous_du,
                                                    previous_dlambda, w));
      start.du = previous_du * scale;
      start.dlambda = previous_dlambda * scale;
      start.r = state.r;  // (40)
      start.previous = previous_backend;

      attempt = StepAttempt();
      attempt.step = step;
      attempt.attempt = cut;
      attempt.kind = ConstraintKind::kArcLength;
      attempt.arc_length = theta;
      attempt.predicted_du = start.du;
      attempt.predicted_dlambda = start.dlambda;
      attempt.result = formulation.Solve(problem, start, options.controls);
      ++summary.attempts;
      const StepPoint& point = attempt.result.point;
      attempt.verdict = Judge(problem, point, options.tolerance);
      attempt.reversed = TurnsBack(point, previous_du, previous_dlambda, step > 1, theta, w);
      attempt.accepted = attempt.verdict.verified && !attempt.reversed;
      attempt.state = {state.u + point.du, point.r, state.lambda + point.dlambda};
      attempt.n_contact = CountContacts(problem, GapsAt(model, attempt.state.u), point.r);
      if (attempt.result.status == Status::kStoppedByCaller) {
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
      theta *= 0.5;
    }
    if (!accepted) {
      summary.status = Status::kFailed;
      summary.message = "step " + std::to_string(step) + " failed the verdict after " +
                        std::to_string(options.max_cutbacks) + " cut-backs of the arc length";
      return summary;
    }
    // The direction to continue in: the increment just taken, or, past a kink, the increment
    // from the kink (the path's direction on the branch it has turned onto). Without this a
    // step that cut across a corner would be continued back along the new branch.
    previous_du = attempt.result.point.du;
    previous_dlambda = attempt.result.point.dlambda;
    if (options.locate_kinks) {
      const std::optional<State> kink = LocateKinks(model, scales, state, attempt.state, step,
                                                    formulation, options, observer, &attempt.kinks);
      summary.kinks += attempt.kinks;
      if (kink) {
        const Vec du_after = attempt.state.u - kink->u;
        const double dl_after = attempt.state.lambda - kink->lambda;
        if (std::sqrt(HInner(du_after, dl_after, du_after, dl_after, w)) > 1e-3 * theta) {
          previous_du = du_after;
          previous_dlambda = dl_after;
        }
      }
    }
    if (observer != nullptr) observer->OnAttempt(attempt);
    previous_backend = attempt.result.backend_state;
    state = attempt.state;
    summary.final_state = state;
    ++summary.accepted_steps;
    theta = std::min(nominal, 2.0 * theta);
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
                           const PathOptions& options, PathObserver* observer) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("path options: " + why);
  StepProblem problem{&model, initial, StepConstraint::FixedLoad(lambda), scales};
  StartPoint start;
  start.kind = options.start;
  start.du = Vec::Zero(model.num_dofs());
  start.dlambda = lambda - initial.lambda;
  start.r = initial.r;
  StepAttempt attempt;
  attempt.step = 1;
  attempt.kind = ConstraintKind::kFixedLoad;
  attempt.predicted_du = start.du;
  attempt.predicted_dlambda = start.dlambda;
  attempt.result = formulation.Solve(problem, start, options.controls);
  attempt.verdict = Judge(problem, attempt.result.point, options.tolerance);
  attempt.accepted = attempt.verdict.verified;
  attempt.state = {initial.u + attempt.result.point.du, attempt.result.point.r,
                   initial.lambda + attempt.result.point.dlambda};
  attempt.n_contact = CountContacts(problem, GapsAt(model, attempt.state.u), attempt.state.r);
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
