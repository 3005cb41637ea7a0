#include "path/kink_location.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "path/arc_length_norm.h"
#include "path/stability.h"
#include "path/step_solve.h"

namespace cb {

KinkLocator::KinkLocator(const ContactModel& model, const ContactScales& scales,
                         Formulation& formulation, const PathOptions& options)
    : model_(model), scales_(scales), formulation_(formulation), options_(options) {}

KinkRecord KinkLocator::SolveFrom(int step, int p, const State& from, const Increment& predicted,
                                  const Vec& r0) const {
  StepProblem kink_step{&model_, from, StepConstraint::Kink(p), scales_};
  StartPoint start;
  start.kind = StartKind::kWarm;
  start.du = predicted.du;
  start.dlambda = predicted.dlambda;
  start.r = r0;
  JudgedStep kink = SolveAndJudge(formulation_, kink_step, start, options_);
  KinkRecord record;
  record.step = step;
  record.pair = p;
  record.result = std::move(kink.result);
  record.verdict = kink.verdict;
  record.state = std::move(kink.state);
  return record;
}

// Solves (53) for pair p from accepted state `from`, predicted at the fraction t of the chord
// towards `to`; on the path between the two states when within two chords of each. (A step may
// cut across a corner of the path, so the kink need not lie inside the chord's ball.)
KinkRecord KinkLocator::Solve(int step, int p, const State& from, const State& to, double t) const {
  const double w = options_.lambda_weight;
  const Vec du_step = to.u - from.u;
  const double dl_step = to.lambda - from.lambda;
  KinkRecord record =
      SolveFrom(step, p, from, {t * du_step, t * dl_step}, from.r + t * (to.r - from.r));
  const double chord = HNorm(du_step, dl_step, w);
  const double from_start = HNorm(record.state.u - from.u, record.state.lambda - from.lambda, w);
  const double to_end = HNorm(to.u - record.state.u, to.lambda - record.state.lambda, w);
  record.between = from_start <= 2.0 * chord && to_end <= 2.0 * chord;
  return record;
}

KinksOfStep KinkLocator::Locate(int step, const State& a, const State& b, PathObserver& observer,
                                int on_kink) const {
  const Vec ga = GapsAt(model_, a.u);
  const Vec gb = GapsAt(model_, b.u);
  const std::vector<bool> ca = ClosedPairs(scales_, ga, a.r);
  const std::vector<bool> cb = ClosedPairs(scales_, gb, b.r);
  KinksOfStep kinks;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (int p = 0; p < model_.num_pairs(); ++p) {
    if (ca[p] == cb[p] || p == on_kink) continue;
    // Switching function s = g/L + r/R changes sign at the kink; interpolate it linearly.
    const double sa = ga[p] / scales_.length + a.r[p] / scales_.force;
    const double sb = gb[p] / scales_.length + b.r[p] / scales_.force;
    const double t = std::clamp(sa / (sa - sb), 0.0, 1.0);
    KinkRecord record = Solve(step, p, a, b, t);
    if (!(record.verdict.verified && record.between)) {
      // From the other end: a may be nearly singular (a bifurcation point a switch leaves
      // from), where a solver that keeps its first Jacobian (Broyden's) cannot converge.
      KinkRecord from_b = Solve(step, p, b, a, 1.0 - t);
      if (from_b.verdict.verified && from_b.between) record = std::move(from_b);
    }
    const double to_b_norm =
        HNorm(b.u - record.state.u, b.lambda - record.state.lambda, options_.lambda_weight);
    if (!(record.verdict.verified && record.between)) ++kinks.not_located;
    if (record.verdict.verified && record.between) {
      ++kinks.found;
      if (to_b_norm < nearest_distance) {
        nearest_distance = to_b_norm;
        kinks.nearest = record.state;
      }
    }
    observer.OnKink(record);
  }
  return kinks;
}

}  // namespace cb
