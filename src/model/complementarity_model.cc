#include "model/complementarity_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cb {

namespace {

bool AllFinite(const SpMat& m) {
  for (int k = 0; k < m.nonZeros(); ++k) {
    if (!std::isfinite(m.valuePtr()[k])) return false;
  }
  return true;
}

}  // namespace

ComplementarityModel ComplementarityModel::Lcp(const SpMat& m, const Vec& q) {
  if (m.rows() < 1 || m.rows() != m.cols()) {
    throw std::invalid_argument("ComplementarityModel: M must be square and non-empty (got " +
                                std::to_string(m.rows()) + " x " + std::to_string(m.cols()) + ")");
  }
  if (q.size() != m.rows()) {
    throw std::invalid_argument("ComplementarityModel: q has size " + std::to_string(q.size()) +
                                ", M is " + std::to_string(m.rows()) + " x " +
                                std::to_string(m.cols()));
  }
  if (!AllFinite(m)) throw std::invalid_argument("ComplementarityModel: M has non-finite entries");
  if (!q.allFinite()) throw std::invalid_argument("ComplementarityModel: q has non-finite entries");
  ComplementarityModel model;
  model.n_ = static_cast<int>(m.rows());
  model.linear_ = true;
  model.m_ = m;
  model.m_.makeCompressed();
  model.q_ = q;
  const SpMat asymmetry = SpMat(m.transpose()) - m;
  double scale = 0.0;
  for (int k = 0; k < model.m_.nonZeros(); ++k) {
    scale = std::max(scale, std::abs(model.m_.valuePtr()[k]));
  }
  double largest = 0.0;
  for (int k = 0; k < asymmetry.nonZeros(); ++k) {
    largest = std::max(largest, std::abs(asymmetry.valuePtr()[k]));
  }
  model.symmetric_ = largest <= 1e-14 * scale;
  model.load_ = Vec::Zero(model.n_);
  return model;
}

ComplementarityModel ComplementarityModel::Lcp(const Mat& m, const Vec& q) {
  if (m.rows() < 1 || m.rows() != m.cols()) {
    throw std::invalid_argument("ComplementarityModel: M must be square and non-empty (got " +
                                std::to_string(m.rows()) + " x " + std::to_string(m.cols()) + ")");
  }
  return Lcp(SpMat(m.sparseView()), q);
}

ComplementarityModel ComplementarityModel::Ncp(int n, Function f, DenseJacobian jacobian) {
  if (n < 1) throw std::invalid_argument("ComplementarityModel: n must be at least 1");
  if (!f) throw std::invalid_argument("ComplementarityModel: F is null");
  if (!jacobian) throw std::invalid_argument("ComplementarityModel: the Jacobian of F is null");
  ComplementarityModel model;
  model.n_ = n;
  model.linear_ = false;
  model.symmetric_ = false;  // a callback F need not be a gradient: no energy
  model.f_ = std::move(f);
  model.jacobian_ = std::move(jacobian);
  model.load_ = Vec::Zero(n);
  return model;
}

void ComplementarityModel::CheckSize(const Vec& u, const char* what) const {
  if (u.size() != n_) {
    throw std::invalid_argument(std::string("ComplementarityModel: ") + what + " has size " +
                                std::to_string(u.size()) + ", expected " + std::to_string(n_));
  }
}

double ComplementarityModel::Energy(const Vec& u) const {
  if (!symmetric_) {
    throw std::invalid_argument(
        "ComplementarityModel: no energy (M is not symmetric, or the problem is an NCP given by "
        "callbacks); check has_energy()");
  }
  CheckSize(u, "u");
  return 0.5 * u.dot(m_ * u) + q_.dot(u);
}

void ComplementarityModel::InternalForce(const Vec& u, Vec* force) const {
  CheckSize(u, "u");
  if (linear_) {
    *force = m_ * u + q_;  // w = M z + q
    return;
  }
  f_(u, force);
  if (force->size() != n_) {
    throw std::invalid_argument("ComplementarityModel: F returned a vector of size " +
                                std::to_string(force->size()) + ", expected " + std::to_string(n_));
  }
}

void ComplementarityModel::Stiffness(const Vec& u, SpMat* stiffness) const {
  CheckSize(u, "u");
  if (linear_) {
    *stiffness = m_;
    return;
  }
  Mat dense;
  jacobian_(u, &dense);
  if (dense.rows() != n_ || dense.cols() != n_) {
    throw std::invalid_argument("ComplementarityModel: the Jacobian of F is " +
                                std::to_string(dense.rows()) + " x " +
                                std::to_string(dense.cols()) + ", expected " + std::to_string(n_) +
                                " x " + std::to_string(n_));
  }
  // Every entry kept (explicit zeros included) so the pattern does not depend on u.
  if (stiffness->rows() != n_ || stiffness->cols() != n_ ||
      stiffness->nonZeros() != static_cast<long>(n_) * n_ || !stiffness->isCompressed()) {
    std::vector<Triplet> all;
    all.reserve(static_cast<std::size_t>(n_) * n_);
    for (int j = 0; j < n_; ++j) {
      for (int i = 0; i < n_; ++i) all.emplace_back(i, j, 1.0);
    }
    stiffness->resize(n_, n_);
    stiffness->setFromTriplets(all.begin(), all.end());
    stiffness->makeCompressed();
  }
  // Column-major with every entry present: values are the dense matrix in column order.
  std::copy(dense.data(), dense.data() + static_cast<std::size_t>(n_) * n_, stiffness->valuePtr());
}

void ComplementarityModel::Gaps(const Vec& u, Vec* phi) const {
  CheckSize(u, "u");
  *phi = -u;  // phi_p = -u_p: the gap is z itself
}

void ComplementarityModel::GapJacobian(const Vec& u, SpMat* jacobian) const {
  CheckSize(u, "u");
  jacobian->resize(n_, n_);
  jacobian->setIdentity();
  *jacobian *= -1.0;
}

void ComplementarityModel::GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const {
  CheckSize(u, "u");
  CheckSize(r, "r");
  *reaction = -r;  // grad phi^T r = -r
}

void ComplementarityModel::GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const {
  CheckSize(u, "u");
  CheckSize(r, "r");
  curvature->resize(n_, n_);  // phi is affine: no curvature
  curvature->setZero();
}

void ComplementarityModel::DataScales(double* length, double* force) const {
  const Vec zero = Vec::Zero(n_);
  Vec w0;
  InternalForce(zero, &w0);
  SpMat jacobian;
  Stiffness(zero, &jacobian);
  const double typical_w = w0.lpNorm<Eigen::Infinity>();
  const double jacobian_norm = (jacobian.cwiseAbs() * Vec::Ones(n_)).maxCoeff();
  const bool sized = typical_w > 0.0 && std::isfinite(typical_w) && jacobian_norm > 0.0 &&
                     std::isfinite(jacobian_norm);
  *force = sized ? typical_w : 1.0;
  *length = sized ? typical_w / jacobian_norm : 1.0;
}

double ComplementarityModel::NaturalResidual(const Vec& z) const {
  Vec w;
  InternalForce(z, &w);
  return z.cwiseMin(w).lpNorm<Eigen::Infinity>();
}

}  // namespace cb
