#include "formulations/external/step_system.h"

#include <limits>

namespace cb {

ExternalStepSystem::ExternalStepSystem(const StepProblem& step) : step_(step), equations_(step) {
  const StepEquationLayout& l = equations_.layout();
  const int kink = step.constraint.kind == ConstraintKind::kKink ? step.constraint.index : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  lower_ = Vec::Constant(l.size(), -kInf);
  upper_ = Vec::Constant(l.size(), kInf);
  for (int i = 0; i < l.complementarity_row(); ++i) rows_.push_back(i);  // (29), (30)
  for (int p = 0; p < l.nc; ++p) {
    if (p == kink) {  // its row g^_p + r^_p is an equation of F
      rows_.push_back(l.complementarity_row() + p);
      continue;
    }
    pair_gaps_.push_back(l.g() + p);
    pair_reactions_.push_back(l.r() + p);
    lower_[l.g() + p] = 0.0;
    upper_[l.r() + p] = 0.0;
  }
  rows_.push_back(l.constraint_row());
}

bool ExternalStepSystem::Residual(const Vec& x, Vec* f) {
  const bool finite = equations_.Residual(x, &all_rows_);
  f->resize(rows());
  for (int i = 0; i < rows(); ++i) (*f)[i] = all_rows_[rows_[i]];
  return finite;
}

SpMat ExternalStepSystem::Jacobian(const Vec& x) {
  SpMat all;
  equations_.Jacobian(x, &all);
  // The kept rows as a selection matrix: F's Jacobian is P J.
  std::vector<Triplet> selection;
  selection.reserve(rows_.size());
  for (int i = 0; i < rows(); ++i) selection.emplace_back(i, rows_[i], 1.0);
  SpMat p(rows(), size());
  p.setFromTriplets(selection.begin(), selection.end());
  SpMat j = p * all;
  j.makeCompressed();
  return j;
}

Vec ExternalStepSystem::Start(const StartPoint& start) const {
  return MakeStepEquationStart(step_, start, size());
}

StepPoint ExternalStepSystem::ToPoint(const Vec& x) const {
  return PointFromScaled(step_, layout(), x);
}

Vec ExternalStepSystem::FromPoint(const StepPoint& point) const {
  const StepEquationLayout& l = layout();
  Vec x(size());
  x.segment(l.du(), l.d) = point.du;
  x.segment(l.g(), l.nc) = point.g / step_.scales.length;
  x.segment(l.r(), l.nc) = point.r / step_.scales.force;
  x[l.dlambda()] = point.dlambda;
  return x;
}

}  // namespace cb
