// `ipopt-energy`'s NLP (EnergyNlp, ipopt_nlp.h).
#include <cmath>
#include <stdexcept>
#include <string>

#include "formulations/common/energy_step.h"
#include "formulations/ipopt/ipopt_nlp.h"
#include "formulations/ipopt/ipopt_sparse.h"

namespace cb {

EnergyNlp::EnergyNlp(const StepProblem& step) : step_(step) {
  step.Validate();
  std::string why;
  if (!IsEnergyStep("ipopt-energy", step, &why)) throw std::invalid_argument(why);
  const ContactModel& model = *step.model;
  const int d = model.num_dofs();
  const int nc = model.num_pairs();
  length_ = step.scales.length;
  force_ = step.scales.force;
  lambda_ = step.constraint.target;
  u_ = step.base.u;
  model.Stiffness(u_, &stiffness_);
  model.GapJacobian(u_, &gap_jacobian_);
  model.GapCurvature(u_, Vec::Zero(nc), &curvature_);
  nnz_stiffness_ = stiffness_.nonZeros();
  nnz_gap_ = gap_jacobian_.nonZeros();
  nnz_curvature_ = curvature_.nonZeros();

  x_lower_ = Vec::Constant(d, -kInfinity);
  x_upper_ = Vec::Constant(d, kInfinity);
  c_lower_ = Vec::Constant(nc, -kInfinity);  // phi / L <= 0, i.e. g >= 0
  c_upper_ = Vec::Zero(nc);
  AppendEntries(gap_jacobian_, 0, 0, false, false, &jacobian_rows_, &jacobian_cols_);
  AppendEntries(stiffness_, 0, 0, false, true, &hessian_rows_, &hessian_cols_);
  AppendEntries(curvature_, 0, 0, false, true, &hessian_rows_, &hessian_cols_);
}

const Vec& EnergyNlp::U(const Vec& x) {
  u_ = step_.base.u + length_ * x;
  return u_;
}

bool EnergyNlp::Objective(const Vec& x, double* f) {
  const Vec& u = U(x);
  const ContactModel& model = *step_.model;
  *f = (model.Energy(u) - lambda_ * model.load_pattern().dot(u)) / (force_ * length_);
  return std::isfinite(*f);
}

bool EnergyNlp::Gradient(const Vec& x, Vec* gradient) {
  const Vec& u = U(x);
  step_.model->InternalForce(u, &work_);
  // d/dx = L d/du: (grad pi - lambda f) L / (R L), the residual of (9) without reactions, / R.
  *gradient = (work_ - lambda_ * step_.model->load_pattern()) / force_;
  return gradient->allFinite();
}

bool EnergyNlp::Constraints(const Vec& x, Vec* c) {
  const Vec& u = U(x);
  step_.model->Gaps(u, &work_);
  *c = work_ / length_;
  return c->allFinite();
}

bool EnergyNlp::JacobianValues(const Vec& x, Vec* values) {
  const Vec& u = U(x);
  step_.model->GapJacobian(u, &gap_jacobian_);
  if (gap_jacobian_.nonZeros() != nnz_gap_) return false;
  values->resize(static_cast<int>(jacobian_rows_.size()));
  int k = 0;
  // d(phi / L)/dx = grad phi (L / L).
  FillEntries(gap_jacobian_, 1.0, false, values->data(), &k);
  return values->allFinite();
}

bool EnergyNlp::HessianValues(const Vec& x, double sigma, const Vec& y, Vec* values) {
  const Vec& u = U(x);
  step_.model->Stiffness(u, &stiffness_);
  step_.model->GapCurvature(u, y, &curvature_);
  if (stiffness_.nonZeros() != nnz_stiffness_ || curvature_.nonZeros() != nnz_curvature_) {
    return false;
  }
  values->resize(static_cast<int>(hessian_rows_.size()));
  int k = 0;
  // sigma L^2 hess pi / (R L) + sum_p y_p L^2 hess phi_p / L.
  FillEntries(stiffness_, sigma * length_ / force_, true, values->data(), &k);
  FillEntries(curvature_, length_, true, values->data(), &k);
  return values->allFinite();
}

}  // namespace cb
