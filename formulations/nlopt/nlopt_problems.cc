#include "formulations/nlopt/nlopt_problems.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseQR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "formulations/common/energy_step.h"

namespace cb {

// --- nlopt-merit ---------------------------------------------------------------------------

NloptMeritObjective::NloptMeritObjective(const StepProblem& step, EtaEquation eta, double scale)
    : system_(step, eta), scale_(scale), root_scale_(std::sqrt(scale)) {}

double NloptMeritObjective::Evaluate(const Vec& y, Vec* gradient) {
  x_ = y / root_scale_;
  if (!system_.Residual(x_, &residual_)) {
    if (gradient != nullptr) gradient->setZero(y.size());
    return std::numeric_limits<double>::infinity();
  }
  if (gradient != nullptr) {
    system_.Jacobian(x_, &jacobian_);
    *gradient = root_scale_ * (jacobian_.transpose() * residual_);  // s J^T F / sqrt(s)
  }
  return scale_ * merit();
}

// --- nlopt-energy --------------------------------------------------------------------------

NloptEnergyProblem::NloptEnergyProblem(const StepProblem& step) : step_(step) {
  std::string why;
  if (!IsEnergyStep("nlopt-energy", step, &why)) throw std::invalid_argument(why);
  lambda_ = step.constraint.target;
}

double NloptEnergyProblem::Objective(const Vec& y, Vec* gradient) const {
  const ContactModel& model = *step_.model;
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const Vec u = step_.base.u + length * y;
  const Vec& f = model.load_pattern();
  if (gradient != nullptr) {
    model.InternalForce(u, gradient);
    *gradient = (*gradient - lambda_ * f) / force;  // L (grad pi - lambda f) / (R L)
  }
  return (model.Energy(u) - lambda_ * f.dot(u)) / (force * length);
}

void NloptEnergyProblem::Constraints(const Vec& y, double* values, double* dense_gradient) const {
  const ContactModel& model = *step_.model;
  const double length = step_.scales.length;
  const Vec u = step_.base.u + length * y;
  Vec phi;
  model.Gaps(u, &phi);
  const int nc = num_constraints();
  const int d = size();
  for (int p = 0; p < nc; ++p) values[p] = phi[p] / length;
  if (dense_gradient == nullptr) return;
  // NLopt's vector-valued constraints take a dense nc x d gradient: nc * d doubles, most of them
  // zero (each row of grad phi touches one node's dofs).
  std::fill(dense_gradient, dense_gradient + static_cast<std::size_t>(nc) * d, 0.0);
  SpMat jacobian;
  model.GapJacobian(u, &jacobian);
  for (int j = 0; j < jacobian.outerSize(); ++j) {
    for (SpMat::InnerIterator it(jacobian, j); it; ++it) {
      // d(phi_p / L)/dy_j = L dphi_p/du_j / L.
      dense_gradient[static_cast<std::size_t>(it.row()) * d + j] = it.value();
    }
  }
}

StepPoint NloptEnergyProblem::Recover(const Vec& y, double active_tol, int* active_pairs) const {
  const ContactModel& model = *step_.model;
  const double length = step_.scales.length;
  const int d = size();
  const int nc = num_constraints();
  StepPoint point;
  point.du = length * y;
  point.dlambda = lambda_ - step_.base.lambda;
  const Vec u = step_.base.u + point.du;
  Vec phi;
  model.Gaps(u, &phi);
  point.g = -phi;
  point.r = Vec::Zero(nc);

  std::vector<int> active;
  for (int p = 0; p < nc; ++p) {
    if (point.g[p] / length <= active_tol) active.push_back(p);
  }
  Vec residual;  // e = grad pi - lambda f, to be balanced by G_A^T r_A, (29)
  model.InternalForce(u, &residual);
  residual -= lambda_ * model.load_pattern();
  SpMat jacobian;
  model.GapJacobian(u, &jacobian);
  const SpMat jacobian_t = jacobian.transpose();  // d x nc, column p = row p of grad phi

  while (!active.empty()) {
    const int m = static_cast<int>(active.size());
    std::vector<Triplet> t;
    for (int k = 0; k < m; ++k) {
      for (SpMat::InnerIterator it(jacobian_t, active[k]); it; ++it) {
        t.emplace_back(it.row(), k, it.value());
      }
    }
    SpMat ga_t(d, m);
    ga_t.setFromTriplets(t.begin(), t.end());
    ga_t.makeCompressed();
    Eigen::SparseQR<SpMat, Eigen::COLAMDOrdering<int>> qr(ga_t);
    Vec ra = Vec::Zero(m);
    if (qr.info() == Eigen::Success) ra = qr.solve(residual);
    if (!ra.allFinite()) ra.setZero();
    int worst = -1;
    for (int k = 0; k < m; ++k) {
      if (ra[k] > 0.0 && (worst < 0 || ra[k] > ra[worst])) worst = k;
    }
    if (worst < 0) {
      for (int k = 0; k < m; ++k) point.r[active[k]] = ra[k];
      break;
    }
    active.erase(active.begin() + worst);  // no adhesion: this pair cannot pull
  }
  if (active_pairs != nullptr) *active_pairs = static_cast<int>(active.size());
  return point;
}

// --- nlopt-mpcc ----------------------------------------------------------------------------

NloptMpccProblem::NloptMpccProblem(const StepProblem& step, double weight)
    : step_(step),
      weight_(weight),
      layout_{step.num_dofs(), step.num_pairs(), /*has_rho=*/true},
      // The eta row is discarded; the nonsmooth case keeps it trivial.
      system_(step, EtaEquation{EtaCase::kNonsmooth, 1.0}) {}

double NloptMpccProblem::Objective(const Vec& z, Vec* gradient) const {
  const auto g = z.segment(layout_.g(), layout_.nc);
  const auto r = z.segment(layout_.r(), layout_.nc);
  if (gradient != nullptr) {
    gradient->setZero(size());
    gradient->segment(layout_.g(), layout_.nc) = -weight_ * r;
    gradient->segment(layout_.r(), layout_.nc) = -weight_ * g;
  }
  return -weight_ * g.dot(r);
}

void NloptMpccProblem::Equalities(const Vec& z, double* values, double* dense_gradient) {
  const int n = size();
  const int rows12 = layout_.d + layout_.nc;      // (29), (30)
  const int step_row = layout_.constraint_row();  // the step constraint, last row of the system
  x_.resize(layout_.size());
  x_.head(n) = z;
  x_[layout_.rho()] = 0.0;
  system_.Residual(x_, &residual_);
  for (int i = 0; i < rows12; ++i) values[i] = residual_[i];
  values[rows12] = residual_[step_row];
  if (dense_gradient == nullptr) return;
  const std::size_t m = static_cast<std::size_t>(num_equalities());
  std::fill(dense_gradient, dense_gradient + m * n, 0.0);
  system_.Jacobian(x_, &jacobian_);
  for (int j = 0; j < n; ++j) {  // the rho column (index n) is dropped
    for (SpMat::InnerIterator it(jacobian_, j); it; ++it) {
      int row = -1;
      if (it.row() < rows12) {
        row = static_cast<int>(it.row());
      } else if (it.row() == step_row) {
        row = rows12;
      }
      if (row >= 0) dense_gradient[static_cast<std::size_t>(row) * n + j] = it.value();
    }
  }
}

void NloptMpccProblem::Bounds(std::vector<double>* lower, std::vector<double>* upper) const {
  const double inf = std::numeric_limits<double>::infinity();
  lower->assign(size(), -inf);
  upper->assign(size(), inf);
  for (int p = 0; p < layout_.nc; ++p) {
    (*lower)[layout_.g() + p] = 0.0;  // g >= 0
    (*upper)[layout_.r() + p] = 0.0;  // r <= 0
  }
}

StepPoint NloptMpccProblem::Point(const Vec& z) const { return PointFromScaled(step_, layout_, z); }

}  // namespace cb
