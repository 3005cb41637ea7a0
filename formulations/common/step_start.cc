// The start points of docs/method.md section 4 in the scaled unknowns (step_equations.h).
#include <cmath>

#include "formulations/common/step_equations.h"

namespace cb {

void FitIncrementToConstraint(const StepProblem& step, Eigen::Ref<Vec> du, double* dlambda) {
  const StepConstraint& c = step.constraint;
  switch (c.kind) {
    case ConstraintKind::kArcLength: {
      const double w = c.lambda_weight;
      const double norm = std::sqrt(du.squaredNorm() + w * w * (*dlambda) * (*dlambda));
      if (norm > 0.0) {
        du *= c.arc_length / norm;
        *dlambda *= c.arc_length / norm;
      } else if (w > 0.0) {
        *dlambda = c.arc_length / w;  // no direction known: a pure load increment
      }
      break;
    }
    case ConstraintKind::kFixedLoad:
      *dlambda = c.target - step.base.lambda;
      break;
    case ConstraintKind::kDisplacement:
      du[c.index] = c.target - step.base.u[c.index];
      break;
    case ConstraintKind::kKink:
      break;  // (53) involves g and r; nothing to fit in the increment
    case ConstraintKind::kHyperplane: {
      // The nearest point of the plane: move along its unit normal.
      const double off = c.arc_length - c.normal.dot(du) - c.normal_lambda * (*dlambda);
      du += off * c.normal;
      *dlambda += off * c.normal_lambda;
      break;
    }
  }
}

Vec MakeStepEquationStart(const StepProblem& step, const StartPoint& start, int size) {
  const ContactModel& model = *step.model;
  const StepEquationLayout layout{model.num_dofs(), model.num_pairs(), false};
  Vec x = Vec::Zero(size);
  Eigen::Ref<Vec> du = x.segment(layout.du(), layout.d);
  auto g = x.segment(layout.g(), layout.nc);
  auto r = x.segment(layout.r(), layout.nc);
  double dlambda = 0.0;
  if (start.kind == StartKind::kWarm) {
    du = start.du;                                 // (38)
    dlambda = start.dlambda;                       // (41)
    FitIncrementToConstraint(step, du, &dlambda);  // (33) holds exactly
    r = start.r / step.scales.force;               // (40)
    Vec phi;
    model.Gaps(step.base.u + du, &phi);
    g = -phi / step.scales.length;  // (39): (30) holds exactly
  } else {
    FitIncrementToConstraint(step, du, &dlambda);  // du0 = 0
    g.setConstant(-1.0);
    r.setConstant(1.0);
  }
  x[layout.dlambda()] = dlambda;
  return x;
}

StepPoint PointFromScaled(const StepProblem& step, const StepEquationLayout& layout, const Vec& x) {
  StepPoint point;
  point.du = x.segment(layout.du(), layout.d);
  point.g = step.scales.length * x.segment(layout.g(), layout.nc);
  point.r = step.scales.force * x.segment(layout.r(), layout.nc);
  point.dlambda = x[layout.dlambda()];
  return point;
}

}  // namespace cb
