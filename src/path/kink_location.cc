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

KinksOfStep KinkLocator::Locate(int step, const State& a, const State& b,
                                PathObserver& observer) const {
  const Vec ga = GapsAt(model_, a.u);
  const Vec gb = GapsAt(model_, b.u);
  const std::vector<bool> ca = ClosedPairs(scales_, ga, a.r);
  const std::vector<bool> cb = ClosedPairs(scales_, gb, b.r);
  const Vec du_step = b.u - a.u;
  const double dl_step = b.lambda - a.lambda;
  const double w = options_.lambda_weight;
  const double chord = HNorm(du_step, dl_step, w);
  KinksOfStep kinks;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (int p = 0; p < model_.num_pairs(); ++p) {
    if (ca[p] == cb[p]) continue;
    // Switching function s = g/L + r/R changes sign at the kink; interpolate it linearly.
    const double sa = ga[p] / scales_.length + a.r[p] / scales_.force;
    const double sb = gb[p] / scales_.length + b.r[p] / scales_.force;
    const double t = std::clamp(sa / (sa - sb), 0.0, 1.0);
    StepProblem kink_step{&model_, a, StepConstraint::Kink(p), scales_};
    StartPoint start;
    start.kind = StartKind::kWarm;
    start.du = t * du_step;
    start.dlambda = t * dl_step;
    start.r = a.r + t * (b.r - a.r);
    JudgedStep kink = SolveAndJudge(formulation_, kink_step, start, options_);
    KinkRecord record;
    record.step = step;
    record.pair = p;
    record.result = std::move(kink.result);
    record.verdict = kink.verdict;
    record.state = std::move(kink.state);
    const Vec& du = record.result.point.du;
    const double dl = record.result.point.dlambda;
    // On the path between the two states: within two chords of each. (A step may cut across a
    // corner of the path, so the kink need not lie inside the chord's ball.)
    const Vec to_b = b.u - record.state.u;
    const double dl_to_b = b.lambda - record.state.lambda;
    const double from_a = HNorm(du, dl, w);
    const double to_b_norm = HNorm(to_b, dl_to_b, w);
    record.between = from_a <= 2.0 * chord && to_b_norm <= 2.0 * chord;
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
