#include "formulations/common/reduced_step_system.h"

#include <algorithm>

#include "core/timer.h"

namespace cb {
namespace {

// Whether some dof of the body is on no pair (at the step's base state): an interior to
// eliminate. A local LCP (an FCLIB file's W) has none, and the reduction would only add work.
bool HasInterior(const StepProblem& step) {
  SpMat g;
  step.model->GapJacobian(step.base.u, &g);
  std::vector<bool> on_a_pair(g.cols(), false);
  for (int k = 0; k < g.outerSize(); ++k) {
    for (SpMat::InnerIterator it(g, k); it; ++it) {
      if (it.value() != 0.0) on_a_pair[it.col()] = true;
    }
  }
  return std::find(on_a_pair.begin(), on_a_pair.end(), false) != on_a_pair.end();
}

}  // namespace

bool ReducedStepSystem::Applies(const StepProblem& step, const std::string& option,
                                std::string* why) {
  const ContactModel& model = *step.model;
  std::string reason;
  if (!model.has_energy() || !model.has_constant_stiffness()) {
    reason = "the body's stiffness changes with u (large deformation or no energy)";
  } else if (step.constraint.kind != ConstraintKind::kFixedLoad) {
    reason = "the step is not at a fixed load (an arc-length path)";
  } else if (step.num_pairs() == 0) {
    reason = "the problem has no contact pairs";
  } else if (!HasInterior(step)) {
    reason = "every dof is on a contact pair (no interior to eliminate)";
  }
  if (reason.empty()) return true;
  if (why != nullptr)
    *why = "option " + option + " (Newton on the contact unknowns) needs " +
           "a fixed-load step of a body with constant stiffness: " + reason;
  return false;
}

ReducedStepSystem::ReducedStepSystem(StepEquationSystem& full)
    : full_(full),
      structure_{0, full.layout().nc,
                 full.structure() != nullptr ? full.structure()->coupling : 1.0,
                 /*dense_stiffness=*/true} {}

bool ReducedStepSystem::Prepare(const Vec& x0) {
  const StepEquationLayout& l = full_.layout();
  x0_ = x0;
  full_.Jacobian(x0, &full_jacobian_);
  Stopwatch factorization;
  if (!elimination_.Factorize(full_jacobian_, l.d, l.nc)) return false;
  times_.factorization_s = factorization.Seconds();
  contact_dofs_ = elimination_.contact_dofs();
  const int c = num_contact_dofs();
  structure_.d = c;
  kept_rows_ = contact_dofs_;
  kept_cols_ = contact_dofs_;
  for (int k = 0; k < 2 * l.nc; ++k) {
    kept_rows_.push_back(l.g() + k);
    kept_cols_.push_back(l.g() + k);
  }
  if (l.has_rho) {
    kept_rows_.push_back(l.extra_row());
    kept_cols_.push_back(l.rho());
  }
  BuildPattern(full_jacobian_);
  // b: the rows (29) / R at du = 0, r^ = 0 and the start's dlambda.
  Vec xb = x0;
  xb.segment(l.du(), l.d).setZero();
  xb.segment(l.r(), l.nc).setZero();
  if (!full_.Residual(xb, &full_residual_)) return false;
  const Vec b = full_residual_.head(l.d);
  Vec b_tilde;
  Stopwatch forward_sweep;
  if (!elimination_.Condense(b, &b_tilde)) return false;
  times_.forward_sweep_s = forward_sweep.Seconds();
  offset_.resize(c);
  for (int k = 0; k < c; ++k) offset_[k] = b_tilde[k] - b[contact_dofs_[k]];
  return true;
}

Vec ReducedStepSystem::Reduce(const Vec& x) const {
  Vec z(size());
  for (int k = 0; k < size(); ++k) z[k] = x[kept_cols_[k]];
  return z;
}

void ReducedStepSystem::Lift(const Vec& z) {
  const StepEquationLayout& l = full_.layout();
  lifted_ = x0_;
  lifted_.segment(l.du(), l.d).setZero();
  for (int k = 0; k < size(); ++k) lifted_[kept_cols_[k]] = z[k];
}

bool ReducedStepSystem::Expand(const Vec& z, Vec* x) {
  const StepEquationLayout& l = full_.layout();
  Lift(z);
  Vec du;
  Stopwatch backward_sweep;
  if (!elimination_.Recover(z.head(num_contact_dofs()), &du)) return false;
  times_.backward_sweep_s = backward_sweep.Seconds();
  *x = lifted_;
  x->segment(l.du(), l.d) = du;
  return true;
}

void ReducedStepSystem::ReduceResidual(const Vec& z, Vec* residual) const {
  residual->resize(size());
  for (int k = 0; k < size(); ++k) (*residual)[k] = full_residual_[kept_rows_[k]];
  const int c = num_contact_dofs();
  residual->head(c) += offset_ + elimination_.correction() * z.head(c);
}

bool ReducedStepSystem::Residual(const Vec& z, Vec* residual) {
  Lift(z);
  if (!full_.Residual(lifted_, &full_residual_)) return false;
  ReduceResidual(z, residual);
  return residual->allFinite();
}

void ReducedStepSystem::Jacobian(const Vec& z, SpMat* jacobian) {
  Lift(z);
  full_.Jacobian(lifted_, &full_jacobian_);
  ReduceJacobian(jacobian);
}

bool ReducedStepSystem::ResidualAndJacobian(const Vec& z, Vec* residual, SpMat* jacobian) {
  Lift(z);
  if (!full_.ResidualAndJacobian(lifted_, &full_residual_, &full_jacobian_)) return false;
  ReduceResidual(z, residual);
  ReduceJacobian(jacobian);
  return residual->allFinite();
}

bool ReducedStepSystem::ResidualFloor(const Vec& z, Vec* floor) {
  Lift(z);
  Vec full_floor;
  if (!full_.ResidualFloor(lifted_, &full_floor)) return false;
  floor->resize(size());
  for (int k = 0; k < size(); ++k) (*floor)[k] = full_floor[kept_rows_[k]];
  return true;
}

void ReducedStepSystem::BuildPattern(const SpMat& full_jacobian) {
  const int n = full_.layout().size();
  const int c = num_contact_dofs();
  std::vector<int> row_of(n, -1), col_of(n, -1);
  for (int k = 0; k < size(); ++k) {
    row_of[kept_rows_[k]] = k;
    col_of[kept_cols_[k]] = k;
  }
  std::vector<Triplet> t;
  for (int a = 0; a < c; ++a) {
    for (int b = 0; b < c; ++b) t.emplace_back(a, b, 0.0);  // T: dense
  }
  for (int k : kept_cols_) {
    for (SpMat::InnerIterator it(full_jacobian, k); it; ++it) {
      const int row = row_of[it.row()];
      if (row >= 0) t.emplace_back(row, col_of[k], 0.0);
    }
  }
  pattern_.resize(size(), size());
  pattern_.setFromTriplets(t.begin(), t.end());
  pattern_.makeCompressed();
  // The slot of (row, col) in pattern_.
  auto slot = [this](int row, int col) {
    const int* begin = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col];
    const int* end = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - pattern_.innerIndexPtr());
  };
  correction_slots_.resize(static_cast<std::size_t>(c) * c);
  for (int b = 0; b < c; ++b) {
    for (int a = 0; a < c; ++a) correction_slots_[static_cast<std::size_t>(b) * c + a] = slot(a, b);
  }
  entry_slots_.clear();
  const int* outer = full_jacobian.outerIndexPtr();
  const int* inner = full_jacobian.innerIndexPtr();
  for (int k : kept_cols_) {
    for (int s = outer[k]; s < outer[k + 1]; ++s) {
      const int row = row_of[inner[s]];
      if (row >= 0) entry_slots_.emplace_back(s, slot(row, col_of[k]));
    }
  }
}

void ReducedStepSystem::ReduceJacobian(SpMat* jacobian) const {
  if (jacobian->nonZeros() != pattern_.nonZeros() || jacobian->rows() != pattern_.rows()) {
    *jacobian = pattern_;
  }
  double* v = jacobian->valuePtr();
  std::fill(v, v + jacobian->nonZeros(), 0.0);
  const double* full = full_jacobian_.valuePtr();
  for (const auto& [from, to] : entry_slots_) v[to] += full[from];
  const Mat& correction = elimination_.correction();
  const int c = num_contact_dofs();
  for (int b = 0; b < c; ++b) {
    for (int a = 0; a < c; ++a) {
      v[correction_slots_[static_cast<std::size_t>(b) * c + a]] += correction(a, b);
    }
  }
}

}  // namespace cb
