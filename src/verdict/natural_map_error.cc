#include "verdict/natural_map_error.h"

#include <Eigen/SparseLU>
#include <cfloat>
#include <cmath>
#include <limits>

#include "model/complementarity_model.h"
#include "model/contact_model.h"

namespace cb {

namespace {

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

// ||min(a, b)||_2: the natural map of the normal components (mu = 0).
double MinMapNorm(const Vec& a, const Vec& b) { return a.cwiseMin(b).norm(); }

// An LCP (ComplementarityModel: the gaps are z, F(z) = W z + q is InternalForce): the local
// error of fc3d_compute_error, u recomputed from z as Siconos does rather than taken from the
// formulation's reactions.
double LocalError(const ContactModel& model, const Vec& z) {
  Vec w, q;
  model.InternalForce(z, &w);
  model.InternalForce(Vec::Zero(z.size()), &q);
  const double residual = MinMapNorm(z, w);
  const double size = q.norm();
  return size > DBL_EPSILON ? residual / size : residual;
}

// A linear body: gfc3d_compute_error's ||v - M^{-1}(f + H r)|| is ||K^{-1} e|| with e the
// equilibrium residual, then the natural map of the contacts, over 1 + ||f||.
double GlobalError(const StepProblem& step, const Vec& u, const Vec& r, double lambda) {
  const ContactModel& model = *step.model;
  Vec internal, phi, reaction;
  model.InternalForce(u, &internal);
  model.Gaps(u, &phi);
  model.GeneralisedReaction(u, r, &reaction);
  const Vec external = lambda * model.load_pattern();
  const Vec equilibrium = internal - external - reaction;
  SpMat stiffness;
  model.Stiffness(u, &stiffness);
  Eigen::SparseLU<SpMat> lu;
  lu.compute(stiffness);
  if (lu.info() != Eigen::Success) return kUndefined;
  const Vec velocity_error = lu.solve(equilibrium);
  if (lu.info() != Eigen::Success) return kUndefined;
  const double contact_error = MinMapNorm(-phi, -r);
  const double residual = std::sqrt(velocity_error.squaredNorm() + contact_error * contact_error);
  return residual / (1.0 + external.norm());
}

}  // namespace

double NaturalMapError(const StepProblem& step, const StepPoint& point) {
  const ContactModel& model = *step.model;
  if (!model.is_linear()) return kUndefined;
  const Vec u = step.base.u + point.du;
  if (dynamic_cast<const ComplementarityModel*>(&model) != nullptr) return LocalError(model, u);
  return GlobalError(step, u, point.r, step.base.lambda + point.dlambda);
}

}  // namespace cb
