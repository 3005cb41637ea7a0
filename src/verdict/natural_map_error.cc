#include "verdict/natural_map_error.h"

#include <Eigen/SparseLU>
#include <algorithm>
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

// Whether K is singular to working precision: then K^{-1} e is rounding amplified (a body
// held by its contacts alone, P1 `block`, has rigid motions in K's null space and gives
// errors of 1e-5 at answers the verdict finds exact to 1e-15). Two steps of inverse iteration
// from a fixed vector estimate 1 / sigma_min; K counts as singular when ||K||_1 / sigma_min
// exceeds kSingularCondition, beyond which eps * cond(K) > 1e-4 and the velocity error has no
// correct digits to speak of. The finite-element FCLIB files have estimates below 1e7, P1's
// free block above 1e13.
constexpr double kSingularCondition = 1e12;

double OneNorm(const SpMat& matrix) {
  double largest = 0.0;
  for (int j = 0; j < matrix.outerSize(); ++j) {
    double column = 0.0;
    for (SpMat::InnerIterator it(matrix, j); it; ++it) column += std::abs(it.value());
    largest = std::max(largest, column);
  }
  return largest;
}

bool NumericallySingular(const SpMat& stiffness, Eigen::SparseLU<SpMat>& lu) {
  Vec y(stiffness.rows());
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = std::sin(1.0 + static_cast<double>(i));
  double growth = 0.0;
  for (int k = 0; k < 2; ++k) {
    y.normalize();
    y = lu.solve(y);
    growth = y.norm();
  }
  return !(growth * OneNorm(stiffness) <= kSingularCondition);  // NaN counts as singular
}

// A linear body: gfc3d_compute_error's ||v - M^{-1}(f + H r)|| is ||K^{-1} e|| with e the
// equilibrium residual, then the natural map of the contacts, over 1 + ||f||.
double GlobalError(const ContactModel& model, const Vec& u, const Vec& r, double lambda) {
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
  if (NumericallySingular(stiffness, lu)) return kUndefined;
  const double contact_error = MinMapNorm(-phi, -r);
  const double residual = std::sqrt(velocity_error.squaredNorm() + contact_error * contact_error);
  return residual / (1.0 + external.norm());
}

}  // namespace

double NaturalMapError(const ContactModel& model, const State& state) {
  if (!model.is_linear()) return kUndefined;
  if (dynamic_cast<const ComplementarityModel*>(&model) != nullptr) {
    return LocalError(model, state.u);
  }
  return GlobalError(model, state.u, state.r, state.lambda);
}

double NaturalMapError(const StepProblem& step, const StepPoint& point) {
  const State& base = step.base;
  return NaturalMapError(*step.model, {base.u + point.du, point.r, base.lambda + point.dlambda});
}

}  // namespace cb
