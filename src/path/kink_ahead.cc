#include "path/kink_ahead.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "path/contact_change_ahead.h"
#include "path/stability.h"
#include "path/step_solve.h"

namespace cb {

KinkAheadFinder::KinkAheadFinder(const ContactModel& model, const ContactScales& scales,
                                 const KinkLocator& locator, const PathOptions& options)
    : model_(model), scales_(scales), locator_(locator), options_(options) {}

std::optional<KinkAhead> KinkAheadFinder::Find(int step, const State& before, const State& at,
                                               const Increment& heading, double reach) const {
  const double w = options_.lambda_weight;
  const double heading_norm = HNorm(heading.du, heading.dlambda, w);
  if (!(heading_norm > 0.0)) return std::nullopt;
  const std::vector<bool> closed_now = ClosedPairs(scales_, GapsAt(model_, at.u), at.r);
  for (const auto& [distance, pair] : SwitchingCrossings(model_, scales_, before, at, reach, w)) {
    const double t = distance / heading_norm;
    Vec r0 = at.r;
    r0[pair] = 0.0;  // the kink's
    KinkRecord kink = locator_.SolveFrom(step, pair, at, {heading.du * t, heading.dlambda * t}, r0);
    const Vec du = kink.state.u - at.u;
    const double dl = kink.state.lambda - at.lambda;
    const bool ahead = HInner(du, dl, heading.du, heading.dlambda, w) > 0.0;
    if (!SolvedAndVerified(kink.result, kink.verdict) || !ahead || HNorm(du, dl, w) > reach)
      continue;
    kink.between = true;
    KinkAhead found{std::move(kink), {}};
    if (PieceTangent(model_, scales_, found.kink.state, pair, !closed_now[pair], w, &found.leave)) {
      return found;
    }
  }
  return std::nullopt;
}

}  // namespace cb
