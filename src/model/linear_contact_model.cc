#include "model/linear_contact_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cb {

namespace {

double LargestMagnitude(const SpMat& m) {
  double largest = 0.0;
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k) {
    const double v = std::abs(m.valuePtr()[k]);
    if (!std::isfinite(v)) return v;
    largest = std::max(largest, v);
  }
  return largest;
}

std::string Size(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

}  // namespace

LinearContactModel::LinearContactModel(const SpMat& stiffness, const SpMat& normals,
                                       const Vec& initial_gaps, const Vec& load_pattern)
    : stiffness_(stiffness), normals_(normals), initial_gaps_(initial_gaps), load_(load_pattern) {
  const Eigen::Index n = stiffness.rows();
  if (n < 1 || stiffness.cols() != n) {
    throw std::invalid_argument("LinearContactModel: K must be square and non-empty, got " +
                                Size(n, stiffness.cols()));
  }
  if (normals.rows() != n) {
    throw std::invalid_argument("LinearContactModel: N is " + Size(normals.rows(), normals.cols()) +
                                ", K is " + Size(n, n) + ": N must have K's rows");
  }
  if (initial_gaps.size() != normals.cols()) {
    throw std::invalid_argument("LinearContactModel: g0 has " +
                                std::to_string(initial_gaps.size()) + " entries, N has " +
                                std::to_string(normals.cols()) + " columns");
  }
  if (load_pattern.size() != n) {
    throw std::invalid_argument("LinearContactModel: f has " + std::to_string(load_pattern.size()) +
                                " entries, K has " + std::to_string(n) + " rows");
  }
  const double scale = LargestMagnitude(stiffness);
  if (!std::isfinite(scale) || !std::isfinite(LargestMagnitude(normals)) ||
      !initial_gaps.allFinite() || !load_pattern.allFinite()) {
    throw std::invalid_argument("LinearContactModel: K, N, g0 and f must be finite");
  }
  const double asymmetry = LargestMagnitude(SpMat(SpMat(stiffness.transpose()) - stiffness));
  if (!(asymmetry <= 1e-14 * scale)) {
    throw std::invalid_argument("LinearContactModel: K is not symmetric: max |K - K^T| = " +
                                std::to_string(asymmetry) + ", max |K| = " + std::to_string(scale));
  }
  stiffness_.makeCompressed();
  normals_.makeCompressed();
  minus_normals_transposed_ = -SpMat(normals_.transpose());
  minus_normals_transposed_.makeCompressed();
}

void LinearContactModel::CheckSize(const Vec& v, Eigen::Index n, const char* what) const {
  if (v.size() != n) {
    throw std::invalid_argument(std::string("LinearContactModel: ") + what + " has size " +
                                std::to_string(v.size()) + ", expected " + std::to_string(n));
  }
}

// pi = 1/2 u^T K u, whose gradient is K u since K = K^T.
double LinearContactModel::Energy(const Vec& u) const {
  CheckSize(u, stiffness_.rows(), "u");
  return 0.5 * u.dot(stiffness_ * u);
}

void LinearContactModel::InternalForce(const Vec& u, Vec* force) const {
  CheckSize(u, stiffness_.rows(), "u");
  *force = stiffness_ * u;
}

void LinearContactModel::Stiffness(const Vec& /*u*/, SpMat* stiffness) const {
  *stiffness = stiffness_;
}

// phi = -(N^T u + g0): positive when the pair overlaps.
void LinearContactModel::Gaps(const Vec& u, Vec* phi) const {
  CheckSize(u, stiffness_.rows(), "u");
  *phi = minus_normals_transposed_ * u - initial_gaps_;
}

void LinearContactModel::GapJacobian(const Vec& /*u*/, SpMat* jacobian) const {
  *jacobian = minus_normals_transposed_;
}

void LinearContactModel::GeneralisedReaction(const Vec& /*u*/, const Vec& r, Vec* reaction) const {
  CheckSize(r, normals_.cols(), "r");
  *reaction = -(normals_ * r);
}

void LinearContactModel::GapCurvature(const Vec& /*u*/, const Vec& /*r*/, SpMat* curvature) const {
  *curvature = SpMat(stiffness_.rows(), stiffness_.rows());
}

}  // namespace cb
