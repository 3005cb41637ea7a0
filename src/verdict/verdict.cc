#include "verdict/verdict.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/complementarity_model.h"

namespace cb {

Verdict Judge(const StepProblem& step, const StepPoint& point, double tolerance) {
  const ContactModel& model = *step.model;
  const int d = model.num_dofs();
  const int nc = model.num_pairs();
  if (point.du.size() != d || point.r.size() != nc) {
    throw std::invalid_argument("Judge: point has the wrong size");
  }
  const double length = step.scales.length;
  const double force = step.scales.force;
  const Vec u = step.base.u + point.du;
  const double lambda = step.base.lambda + point.dlambda;

  Vec internal, phi, reaction;
  model.InternalForce(u, &internal);
  model.Gaps(u, &phi);
  model.GeneralisedReaction(u, point.r, &reaction);
  const Vec external = lambda * model.load_pattern();
  const Vec equilibrium = internal - external - reaction;
  const Vec g = -phi;

  Verdict v;
  // A body's equilibrium is judged relative to its load; an LCP/NCP has no load (lambda f = 0)
  // and its rows F(z) + r are reactions, judged relative to R like the reactions of (10)-(11):
  // otherwise the verdict on an LCP would depend on the units of its data.
  const bool complementarity = dynamic_cast<const ComplementarityModel*>(&model) != nullptr;
  const double equilibrium_scale =
      complementarity ? force : std::max(1.0, d > 0 ? external.lpNorm<Eigen::Infinity>() : 0.0);
  v.eq_res = (d > 0 ? equilibrium.lpNorm<Eigen::Infinity>() : 0.0) / equilibrium_scale;
  v.comp_res = 0.0;
  v.feas_res = 0.0;
  for (int p = 0; p < nc; ++p) {
    const double gs = g[p] / length;
    const double rs = point.r[p] / force;
    v.comp_res = std::max(v.comp_res, std::abs(std::min(gs, -rs)));
    v.feas_res = std::max({v.feas_res, -gs, rs});
  }
  v.tolerance = tolerance;
  v.step_res = std::abs(StepConstraintValue(step, point.du, point.dlambda, g, point.r));
  // NaN compares false: a non-finite residual never verifies.
  v.verified = v.eq_res <= tolerance && v.comp_res <= tolerance && v.feas_res <= tolerance &&
               v.step_res <= tolerance && std::isfinite(point.dlambda);
  return v;
}

int CountContacts(const StepProblem& step, const Vec& g, const Vec& r) {
  int count = 0;
  for (int p = 0; p < g.size(); ++p) {
    if (g[p] / step.scales.length < -r[p] / step.scales.force) ++count;
  }
  return count;
}

}  // namespace cb
