#include "step/step_problem.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace cb {

const char* ToString(ConstraintKind kind) {
  switch (kind) {
    case ConstraintKind::kArcLength:
      return "arc-length";
    case ConstraintKind::kFixedLoad:
      return "fixed-load";
    case ConstraintKind::kDisplacement:
      return "displacement";
    case ConstraintKind::kKink:
      return "kink";
    case ConstraintKind::kHyperplane:
      return "hyperplane";
  }
  return "unknown";
}

StepConstraint StepConstraint::ArcLength(double theta, double lambda_weight) {
  StepConstraint c;
  c.kind = ConstraintKind::kArcLength;
  c.arc_length = theta;
  c.lambda_weight = lambda_weight;
  return c;
}

StepConstraint StepConstraint::FixedLoad(double lambda) {
  StepConstraint c;
  c.kind = ConstraintKind::kFixedLoad;
  c.target = lambda;
  return c;
}

StepConstraint StepConstraint::Displacement(int dof, double value) {
  StepConstraint c;
  c.kind = ConstraintKind::kDisplacement;
  c.index = dof;
  c.target = value;
  return c;
}

StepConstraint StepConstraint::Kink(int pair) {
  StepConstraint c;
  c.kind = ConstraintKind::kKink;
  c.index = pair;
  return c;
}

StepConstraint StepConstraint::Hyperplane(Vec normal, double normal_lambda, double theta) {
  StepConstraint c;
  c.kind = ConstraintKind::kHyperplane;
  c.arc_length = theta;
  const double norm = std::sqrt(normal.squaredNorm() + normal_lambda * normal_lambda);
  c.normal = norm > 0.0 ? Vec(normal / norm) : std::move(normal);
  c.normal_lambda = norm > 0.0 ? normal_lambda / norm : normal_lambda;
  return c;
}

void StepProblem::Validate() const {
  if (model == nullptr) throw std::invalid_argument("step.model is null");
  const int d = model->num_dofs();
  const int nc = model->num_pairs();
  if (base.u.size() != d) throw std::invalid_argument("step.base.u has the wrong size");
  if (base.r.size() != nc) throw std::invalid_argument("step.base.r has the wrong size");
  if (!std::isfinite(base.lambda)) throw std::invalid_argument("step.base.lambda is not finite");
  if (!(scales.length > 0.0) || !std::isfinite(scales.length)) {
    throw std::invalid_argument("step.scales.length must be positive and finite");
  }
  if (!(scales.force > 0.0) || !std::isfinite(scales.force)) {
    throw std::invalid_argument("step.scales.force must be positive and finite");
  }
  switch (constraint.kind) {
    case ConstraintKind::kArcLength:
      if (!(constraint.arc_length > 0.0) || !std::isfinite(constraint.arc_length)) {
        throw std::invalid_argument("step.constraint.arc_length must be positive and finite");
      }
      if (!(constraint.lambda_weight >= 0.0) || !std::isfinite(constraint.lambda_weight)) {
        throw std::invalid_argument("step.constraint.lambda_weight must be >= 0 and finite");
      }
      break;
    case ConstraintKind::kFixedLoad:
      if (!std::isfinite(constraint.target)) {
        throw std::invalid_argument("step.constraint.target (lambda) is not finite");
      }
      break;
    case ConstraintKind::kDisplacement:
      if (constraint.index < 0 || constraint.index >= d) {
        throw std::invalid_argument("step.constraint.index is not a dof");
      }
      if (!std::isfinite(constraint.target)) {
        throw std::invalid_argument("step.constraint.target (displacement) is not finite");
      }
      break;
    case ConstraintKind::kKink:
      if (constraint.index < 0 || constraint.index >= nc) {
        throw std::invalid_argument("step.constraint.index is not a contact pair");
      }
      break;
    case ConstraintKind::kHyperplane:
      if (!(constraint.arc_length > 0.0) || !std::isfinite(constraint.arc_length)) {
        throw std::invalid_argument("step.constraint.arc_length must be positive and finite");
      }
      if (constraint.normal.size() != d) {
        throw std::invalid_argument("step.constraint.normal has the wrong size");
      }
      if (!constraint.normal.allFinite() || !std::isfinite(constraint.normal_lambda) ||
          !(constraint.normal.squaredNorm() + constraint.normal_lambda * constraint.normal_lambda >
            0.0)) {
        throw std::invalid_argument("step.constraint.normal must be finite and nonzero");
      }
      break;
  }
}

double StepConstraintValue(const StepProblem& step, const Vec& du, double dlambda, const Vec& g,
                           const Vec& r) {
  const StepConstraint& c = step.constraint;
  switch (c.kind) {
    case ConstraintKind::kArcLength: {
      const double w = c.lambda_weight;
      return (du.squaredNorm() + w * w * dlambda * dlambda) / (c.arc_length * c.arc_length) - 1.0;
    }
    case ConstraintKind::kFixedLoad:
      return dlambda - (c.target - step.base.lambda);
    case ConstraintKind::kDisplacement:
      return (step.base.u[c.index] + du[c.index] - c.target) / step.scales.length;
    case ConstraintKind::kKink:
      return g[c.index] / step.scales.length - r[c.index] / step.scales.force;
    case ConstraintKind::kHyperplane:
      return (c.normal.dot(du) + c.normal_lambda * dlambda) / c.arc_length - 1.0;
  }
  return 0.0;
}

}  // namespace cb
