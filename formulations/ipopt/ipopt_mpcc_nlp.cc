// `ipopt-mpcc`'s NLP (MpccNlp, ipopt_nlp.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "formulations/ipopt/ipopt_colouring.h"
#include "formulations/ipopt/ipopt_nlp.h"
#include "formulations/ipopt/ipopt_sparse.h"

namespace cb {

const char* ToString(MpccReformulation reformulation) {
  return reformulation == MpccReformulation::kScholtes ? "scholtes" : "penalty";
}

MpccNlp::MpccNlp(const StepProblem& step, MpccReformulation reformulation, double penalty_weight)
    : step_(step), reformulation_(reformulation), penalty_weight_(penalty_weight) {
  step.Validate();
  if (!(penalty_weight > 0.0) || !std::isfinite(penalty_weight)) {
    throw std::invalid_argument("ipopt-mpcc: penalty_weight must be positive and finite");
  }
  const ContactModel& model = *step.model;
  d_ = model.num_dofs();
  nc_ = model.num_pairs();
  length_ = step.scales.length;
  force_ = step.scales.force;
  linear_ = model.is_linear();
  has_step_row_ = step.constraint.kind != ConstraintKind::kKink;
  const Vec& f = model.load_pattern();
  for (int i = 0; i < d_; ++i) {
    if (f[i] != 0.0) load_rows_.push_back(i);
  }

  u_ = step.base.u;
  model.Stiffness(u_, &stiffness_);
  model.GapJacobian(u_, &gap_jacobian_);
  model.GapCurvature(u_, step.base.r, &curvature_);
  nnz_stiffness_ = stiffness_.nonZeros();
  nnz_gap_ = gap_jacobian_.nonZeros();
  nnz_curvature_ = curvature_.nonZeros();
  curved_ = nnz_curvature_ > 0;

  BuildJointPattern();
  SetBounds();
  AppendJacobianStructure();
  AppendHessianStructure();
}

void MpccNlp::BuildJointPattern() {
  // Joint symmetric pattern of stiffness (and its transpose) and curvature.
  std::vector<Triplet> t;
  for (int j = 0; j < stiffness_.outerSize(); ++j) {
    for (SpMat::InnerIterator it(stiffness_, j); it; ++it) {
      t.emplace_back(it.row(), j, 1.0);
      t.emplace_back(j, it.row(), 1.0);
    }
  }
  for (int j = 0; j < curvature_.outerSize(); ++j) {
    for (SpMat::InnerIterator it(curvature_, j); it; ++it) t.emplace_back(it.row(), j, 1.0);
  }
  joint_.resize(d_, d_);
  joint_.setFromTriplets(t.begin(), t.end());
  joint_.makeCompressed();

  const int nnz_joint = static_cast<int>(joint_.nonZeros());
  joint_transpose_.assign(nnz_joint, -1);
  joint_lower_slot_.assign(nnz_joint, -1);
  for (int j = 0; j < d_; ++j) {
    for (int k = joint_.outerIndexPtr()[j]; k < joint_.outerIndexPtr()[j + 1]; ++k) {
      joint_transpose_[k] = FindEntry(joint_, j, joint_.innerIndexPtr()[k]);
    }
  }
  curvature_to_joint_.clear();
  for (int j = 0; j < curvature_.outerSize(); ++j) {
    for (SpMat::InnerIterator it(curvature_, j); it; ++it) {
      curvature_to_joint_.push_back(FindEntry(joint_, static_cast<int>(it.row()), j));
    }
  }
  // The colouring of the finite differences (ThirdOrderTerm); none for a linear model.
  colour_.assign(d_, -1);
  num_colours_ = linear_ ? 0 : ColourColumns(joint_, &colour_);
}

void MpccNlp::SetBounds() {
  // Bounds (11): g^ >= 0, r^ <= 0; the kink pair fixed at 0 (see the class comment).
  const int n = d_ + 2 * nc_ + 1;
  x_lower_ = Vec::Constant(n, -kInfinity);
  x_upper_ = Vec::Constant(n, kInfinity);
  x_lower_.segment(ix_g(), nc_).setZero();
  x_upper_.segment(ix_r(), nc_).setZero();
  if (!has_step_row_) {
    const int p = step_.constraint.index;
    x_upper_[ix_g() + p] = 0.0;
    x_lower_[ix_r() + p] = 0.0;
  }
  const int m = row_scholtes() + (reformulation_ == MpccReformulation::kScholtes ? nc_ : 0);
  c_lower_ = Vec::Zero(m);
  c_upper_ = Vec::Zero(m);
  if (reformulation_ == MpccReformulation::kScholtes) {
    c_lower_.tail(nc_).setConstant(-kInfinity);
    c_upper_.tail(nc_).setConstant(relaxation_);
  }
}

void MpccNlp::AppendJacobianStructure() {
  // In the order JacobianValues fills it.
  auto& jr = jacobian_rows_;
  auto& jc = jacobian_cols_;
  AppendEntries(stiffness_, 0, ix_u(), false, false, &jr, &jc);    // dF1/dx_u, stiffness
  AppendEntries(curvature_, 0, ix_u(), false, false, &jr, &jc);    // dF1/dx_u, curvature
  AppendEntries(gap_jacobian_, 0, ix_r(), true, false, &jr, &jc);  // dF1/dr^
  for (int i : load_rows_) {                                       // dF1/ddlambda
    jr.push_back(i);
    jc.push_back(ix_dlambda());
  }
  AppendEntries(gap_jacobian_, d_, ix_u(), false, false, &jr, &jc);  // dF2/dx_u
  for (int p = 0; p < nc_; ++p) {                                    // dF2/dg^
    jr.push_back(d_ + p);
    jc.push_back(ix_g() + p);
  }
  if (has_step_row_) {
    const StepConstraint& c = step_.constraint;
    switch (c.kind) {
      case ConstraintKind::kArcLength:
      case ConstraintKind::kHyperplane:
        for (int j = 0; j < d_; ++j) {
          jr.push_back(row_step());
          jc.push_back(ix_u() + j);
        }
        jr.push_back(row_step());
        jc.push_back(ix_dlambda());
        break;
      case ConstraintKind::kFixedLoad:
        jr.push_back(row_step());
        jc.push_back(ix_dlambda());
        break;
      case ConstraintKind::kDisplacement:
        jr.push_back(row_step());
        jc.push_back(ix_u() + c.index);
        break;
      case ConstraintKind::kKink:
        break;
    }
  }
  if (reformulation_ == MpccReformulation::kScholtes) {
    for (int p = 0; p < nc_; ++p) {
      jr.push_back(row_scholtes() + p);
      jc.push_back(ix_g() + p);
      jr.push_back(row_scholtes() + p);
      jc.push_back(ix_r() + p);
    }
  }
}

void MpccNlp::AppendHessianStructure() {
  // The lower triangle, in the order HessianValues fills it.
  auto& hr = hessian_rows_;
  auto& hc = hessian_cols_;
  for (int j = 0; j < d_; ++j) {
    for (int k = joint_.outerIndexPtr()[j]; k < joint_.outerIndexPtr()[j + 1]; ++k) {
      const int i = joint_.innerIndexPtr()[k];
      if (i < j) continue;
      joint_lower_slot_[k] = static_cast<int>(hr.size());
      hr.push_back(i);
      hc.push_back(j);
    }
  }
  if (has_step_row_ && step_.constraint.kind == ConstraintKind::kArcLength) {
    for (int j = 0; j < d_; ++j) {
      hr.push_back(j);
      hc.push_back(j);
    }
    hr.push_back(ix_dlambda());
    hc.push_back(ix_dlambda());
  }
  first_cross_ = static_cast<int>(hr.size());
  if (curved_) {
    AppendEntries(gap_jacobian_, ix_r(), ix_u(), false, false, &hr, &hc);  // (r^_p, x_u)
  }
  for (int p = 0; p < nc_; ++p) {  // (r^_p, g^_p): the complementarity product
    hr.push_back(ix_r() + p);
    hc.push_back(ix_g() + p);
  }
}

void MpccNlp::set_relaxation(double t) {
  relaxation_ = t;
  if (reformulation_ == MpccReformulation::kScholtes) c_upper_.tail(nc_).setConstant(t);
}

bool MpccNlp::Evaluate(const Vec& x) {
  const ContactModel& model = *step_.model;
  u_ = step_.base.u + length_ * x.segment(ix_u(), d_);
  model.Stiffness(u_, &stiffness_);
  model.GapJacobian(u_, &gap_jacobian_);
  model.GapCurvature(u_, force_ * x.segment(ix_r(), nc_), &curvature_);
  return stiffness_.nonZeros() == nnz_stiffness_ && gap_jacobian_.nonZeros() == nnz_gap_ &&
         curvature_.nonZeros() == nnz_curvature_;
}

bool MpccNlp::Objective(const Vec& x, double* f) {
  *f = 0.0;
  if (reformulation_ == MpccReformulation::kPenalty) {
    // Exact penalty of (11): sum_p (-g^_p r^_p) >= 0 on the bounds, 0 exactly at complementarity.
    *f = -penalty_weight_ * x.segment(ix_g(), nc_).dot(x.segment(ix_r(), nc_));
  }
  return std::isfinite(*f);
}

bool MpccNlp::Gradient(const Vec& x, Vec* gradient) {
  gradient->setZero(x.size());
  if (reformulation_ == MpccReformulation::kPenalty) {
    gradient->segment(ix_g(), nc_) = -penalty_weight_ * x.segment(ix_r(), nc_);
    gradient->segment(ix_r(), nc_) = -penalty_weight_ * x.segment(ix_g(), nc_);
  }
  return gradient->allFinite();
}

bool MpccNlp::Constraints(const Vec& x, Vec* c) {
  const ContactModel& model = *step_.model;
  const auto xu = x.segment(ix_u(), d_);
  const auto g = x.segment(ix_g(), nc_);
  const auto r = x.segment(ix_r(), nc_);
  const double dlambda = x[ix_dlambda()];
  u_ = step_.base.u + length_ * xu;
  c->resize(num_constraints());
  model.InternalForce(u_, &work_);
  Vec reaction;
  model.GeneralisedReaction(u_, r, &reaction);
  c->segment(0, d_) = (work_ - (step_.base.lambda + dlambda) * model.load_pattern()) / force_ -
                      reaction;  // (29) / R
  model.Gaps(u_, &work_);
  c->segment(d_, nc_) = g + work_ / length_;  // (30) / L
  if (has_step_row_) {
    (*c)[row_step()] = StepConstraintValue(step_, length_ * xu, dlambda, length_ * g, force_ * r);
  }
  if (reformulation_ == MpccReformulation::kScholtes) {
    c->segment(row_scholtes(), nc_) = -g.cwiseProduct(r);  // -g^_p r^_p <= t
  }
  return c->allFinite();
}

bool MpccNlp::JacobianValues(const Vec& x, Vec* values) {
  if (!Evaluate(x)) return false;
  const auto xu = x.segment(ix_u(), d_);
  const auto g = x.segment(ix_g(), nc_);
  const auto r = x.segment(ix_r(), nc_);
  values->resize(static_cast<int>(jacobian_rows_.size()));
  double* v = values->data();
  int k = 0;
  // dF1/dx_u = (L / R)(hess pi - sum_p r_p hess phi_p), dF1/dr^ = -grad phi^T,
  // dF1/ddlambda = -f / R.
  FillEntries(stiffness_, length_ / force_, false, v, &k);
  FillEntries(curvature_, -length_ / force_, false, v, &k);
  FillEntries(gap_jacobian_, -1.0, false, v, &k);
  const Vec& f = step_.model->load_pattern();
  for (int i : load_rows_) v[k++] = -f[i] / force_;
  // dF2/dx_u = grad phi, dF2/dg^ = I.
  FillEntries(gap_jacobian_, 1.0, false, v, &k);
  for (int p = 0; p < nc_; ++p) v[k++] = 1.0;
  if (has_step_row_) {
    const StepConstraint& c = step_.constraint;
    switch (c.kind) {
      case ConstraintKind::kArcLength: {
        // (33) / theta^2 - 1 with du = L x_u.
        const double t2 = c.arc_length * c.arc_length;
        for (int j = 0; j < d_; ++j) v[k++] = 2.0 * length_ * length_ * xu[j] / t2;
        v[k++] = 2.0 * c.lambda_weight * c.lambda_weight * x[ix_dlambda()] / t2;
        break;
      }
      case ConstraintKind::kFixedLoad:     // dlambda - target
      case ConstraintKind::kDisplacement:  // (u_j - target) / L with u_j = u^k_j + L x_j
        v[k++] = 1.0;
        break;
      case ConstraintKind::kKink:
        break;
      case ConstraintKind::kHyperplane:  // (n . L x_u + n_lambda dlambda) / theta - 1
        for (int j = 0; j < d_; ++j) v[k++] = length_ * c.normal[j] / c.arc_length;
        v[k++] = c.normal_lambda / c.arc_length;
        break;
    }
  }
  if (reformulation_ == MpccReformulation::kScholtes) {
    for (int p = 0; p < nc_; ++p) {
      v[k++] = -r[p];
      v[k++] = -g[p];
    }
  }
  return values->allFinite();
}

bool MpccNlp::ThirdOrderTerm(const Vec& x, const Vec& y, Vec* joint_values) {
  // v(u) = (hess pi(u)^T - sum_p r_p hess phi_p(u)) y is the u-gradient of y^T F1 R; its
  // Jacobian, by central differences per colour, is the block the model cannot give.
  const int nnz = static_cast<int>(joint_.nonZeros());
  joint_values->setZero(nnz);
  if (linear_ || y.lpNorm<Eigen::Infinity>() == 0.0) return true;
  const ContactModel& model = *step_.model;
  const Vec u = step_.base.u + length_ * x.segment(ix_u(), d_);
  const Vec r = force_ * x.segment(ix_r(), nc_);
  // Step: the cube root of the rounding unit times the problem's displacement size.
  const double h = 6e-6 * std::max(length_, u.lpNorm<Eigen::Infinity>());
  auto v = [&](const Vec& at, Vec* out) {
    model.Stiffness(at, &work_stiffness_);
    model.GapCurvature(at, r, &work_curvature_);
    if (work_stiffness_.nonZeros() != nnz_stiffness_ ||
        work_curvature_.nonZeros() != nnz_curvature_) {
      return false;
    }
    *out = work_stiffness_.transpose() * y - work_curvature_ * y;
    return true;
  };
  const int* outer = joint_.outerIndexPtr();
  const int* inner = joint_.innerIndexPtr();
  Vec at;
  for (int c = 0; c < num_colours_; ++c) {
    at = u;
    for (int j = 0; j < d_; ++j) {
      if (colour_[j] == c) at[j] += h;
    }
    if (!v(at, &v_plus_)) return false;
    at = u;
    for (int j = 0; j < d_; ++j) {
      if (colour_[j] == c) at[j] -= h;
    }
    if (!v(at, &v_minus_)) return false;
    for (int j = 0; j < d_; ++j) {
      if (colour_[j] != c) continue;
      for (int a = outer[j]; a < outer[j + 1]; ++a) {
        (*joint_values)[a] = (v_plus_[inner[a]] - v_minus_[inner[a]]) / (2.0 * h);
      }
    }
  }
  return true;
}

bool MpccNlp::HessianValues(const Vec& x, double sigma, const Vec& y, Vec* values) {
  const ContactModel& model = *step_.model;
  const Vec y1 = y.segment(0, d_);    // multipliers of (29) / R
  const Vec y2 = y.segment(d_, nc_);  // multipliers of (30) / L
  const double ys = has_step_row_ ? y[row_step()] : 0.0;
  u_ = step_.base.u + length_ * x.segment(ix_u(), d_);
  values->setZero(static_cast<int>(hessian_rows_.size()));
  double* v = values->data();

  // (x_u, x_u): (L^2 / R) d/du[(hess pi^T - sum_p r_p hess phi_p) y1] (symmetrised), plus
  // L sum_p y2_p hess phi_p from (30) / L.
  Vec third;
  if (!ThirdOrderTerm(x, y1, &third)) return false;
  const double scale3 = length_ * length_ / force_;
  for (int k = 0; k < static_cast<int>(joint_lower_slot_.size()); ++k) {
    const int slot = joint_lower_slot_[k];
    if (slot < 0) continue;
    v[slot] = scale3 * 0.5 * (third[k] + third[joint_transpose_[k]]);
  }
  if (curved_) {
    model.GapCurvature(u_, y2, &work_curvature_);
    if (work_curvature_.nonZeros() != nnz_curvature_) return false;
    int e = 0;
    for (int j = 0; j < work_curvature_.outerSize(); ++j) {
      for (SpMat::InnerIterator it(work_curvature_, j); it; ++it, ++e) {
        const int slot = joint_lower_slot_[curvature_to_joint_[e]];
        if (slot >= 0) v[slot] += length_ * it.value();
      }
    }
  }
  int k = 0;
  for (int slot : joint_lower_slot_) k += slot >= 0 ? 1 : 0;
  if (has_step_row_ && step_.constraint.kind == ConstraintKind::kArcLength) {
    const StepConstraint& c = step_.constraint;
    const double t2 = c.arc_length * c.arc_length;
    for (int j = 0; j < d_; ++j) v[k++] = ys * 2.0 * length_ * length_ / t2;
    v[k++] = ys * 2.0 * c.lambda_weight * c.lambda_weight / t2;
  }
  if (curved_) {
    // (r^_p, x_u): d/dx_u of -(grad phi^T y1)_p = -L hess phi_p y1, on pair p's dofs (the
    // columns of its gap-Jacobian row). hess phi_p is GapCurvature with r = e_p.
    std::vector<Vec> hy(nc_);
    if (y1.lpNorm<Eigen::Infinity>() > 0.0) {
      Vec unit = Vec::Zero(nc_);
      for (int p = 0; p < nc_; ++p) {
        unit[p] = 1.0;
        model.GapCurvature(u_, unit, &work_curvature_);
        unit[p] = 0.0;
        hy[p] = work_curvature_ * y1;
      }
    }
    model.GapJacobian(u_, &gap_jacobian_);
    if (gap_jacobian_.nonZeros() != nnz_gap_) return false;
    for (int j = 0; j < gap_jacobian_.outerSize(); ++j) {
      for (SpMat::InnerIterator it(gap_jacobian_, j); it; ++it) {
        const int p = static_cast<int>(it.row());
        v[k++] = hy[p].size() > 0 ? -length_ * hy[p][j] : 0.0;
      }
    }
  }
  for (int p = 0; p < nc_; ++p) {
    // (r^_p, g^_p): -y_S,p from the Scholtes row -g^ r^ <= t, or -sigma w from the penalty.
    v[k++] = reformulation_ == MpccReformulation::kScholtes ? -y[row_scholtes() + p]
                                                            : -sigma * penalty_weight_;
  }
  return values->allFinite();
}

}  // namespace cb
