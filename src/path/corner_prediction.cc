#include "path/corner_prediction.h"

#include <vector>

#include "path/contact_change_ahead.h"
#include "path/stability.h"

namespace cb {

std::optional<Increment> CornerPrediction(const ContactModel& model, const ContactScales& scales,
                                          const State& before, const State& at,
                                          const Increment& prediction, double lambda_weight) {
  const double w = lambda_weight;
  const double theta = HNorm(prediction.du, prediction.dlambda, w);
  const double chord = HNorm(at.u - before.u, at.lambda - before.lambda, w);
  if (!(theta > 0.0) || !(chord > 0.0)) return std::nullopt;
  const std::vector<std::pair<double, int>> crossings =
      SwitchingCrossings(model, scales, before, at, theta, w);
  if (crossings.empty()) return std::nullopt;
  const auto [distance, pair] = crossings.front();
  // The corner: along the prediction, the reactions extrapolated as the switching function was,
  // the pair's at its kink value 0.
  const double t = distance / theta;
  State corner = at;
  corner.u = at.u + prediction.du * t;
  corner.lambda = at.lambda + prediction.dlambda * t;
  corner.r = at.r + (at.r - before.r) * (distance / chord);
  corner.r[pair] = 0.0;
  const bool closed_now = ClosedPairs(scales, GapsAt(model, at.u), at.r)[pair];
  Increment piece;
  if (!PieceTangent(model, scales, corner, pair, !closed_now, w, &piece)) return std::nullopt;
  const double rest = theta - distance;
  return Increment{prediction.du * t + piece.du * rest,
                   prediction.dlambda * t + piece.dlambda * rest};
}

}  // namespace cb
