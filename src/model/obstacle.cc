#include "model/obstacle.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace cb {
namespace {

std::string FormatPoint(const Point& x) {
  std::ostringstream out;
  out << "(";
  for (int i = 0; i < x.size(); ++i) out << (i > 0 ? ", " : "") << x[i];
  out << ")";
  return out.str();
}

bool IsSupportedDim(Eigen::Index dim) { return dim == 2 || dim == 3; }

void CheckPoint(const Obstacle& obstacle, const Point& x) {
  if (x.size() != obstacle.dim()) {
    throw std::invalid_argument("Obstacle: the point has dimension " + std::to_string(x.size()) +
                                ", the obstacle " + std::to_string(obstacle.dim()));
  }
}

}  // namespace

double Obstacle::Value(const Point& x) const {
  CheckPoint(*this, x);
  ObstacleLocal local;
  Evaluate(x.data(), Order::kValue, &local);
  return local.value;
}

Point Obstacle::Gradient(const Point& x) const {
  CheckPoint(*this, x);
  ObstacleLocal local;
  Evaluate(x.data(), Order::kGradient, &local);
  return Eigen::Map<const Point>(local.gradient, dim());
}

PointMat Obstacle::Hessian(const Point& x) const {
  CheckPoint(*this, x);
  ObstacleLocal local;
  Evaluate(x.data(), Order::kHessian, &local);
  PointMat h(dim(), dim());
  for (int a = 0; a < dim(); ++a) {
    for (int b = 0; b < dim(); ++b) h(a, b) = local.hessian[a][b];
  }
  return h;
}

// --- HalfSpace: varphi(x) = n.(x - p), an affine function with |grad varphi| = 1 -------------

HalfSpace::HalfSpace(Point point, Point normal)
    : point_(std::move(point)), normal_(std::move(normal)) {
  if (!IsSupportedDim(point_.size())) {
    throw std::invalid_argument("HalfSpace: the point has dimension " +
                                std::to_string(point_.size()) + ", expected 2 or 3");
  }
  if (normal_.size() != point_.size()) {
    throw std::invalid_argument("HalfSpace: the normal has dimension " +
                                std::to_string(normal_.size()) + " but the point has " +
                                std::to_string(point_.size()));
  }
  if (!point_.allFinite() || !normal_.allFinite()) {
    throw std::invalid_argument("HalfSpace: non-finite point or normal");
  }
  const double length = normal_.norm();
  if (!(length > 0.0)) throw std::invalid_argument("HalfSpace: zero normal");
  // Normalised so that varphi is a signed distance (|grad varphi| = 1, docs/method.md section 1).
  normal_ /= length;
}

std::string HalfSpace::Describe() const {
  return std::string(dim() == 2 ? "half-plane" : "half-space") +
         " n.(x - p) > 0 with p = " + FormatPoint(point_) + ", n = " + FormatPoint(normal_);
}

void HalfSpace::Evaluate(const double* x, Order order, ObstacleLocal* out) const {
  const int d = dim();
  out->value = 0.0;
  for (int c = 0; c < d; ++c) out->value += normal_[c] * (x[c] - point_[c]);
  if (order == Order::kValue) return;
  for (int c = 0; c < d; ++c) out->gradient[c] = normal_[c];
  // The Hessian is zero: ObstacleLocal starts zeroed and nothing here writes to it.
}

// --- Ball: varphi(x) = s (|x - c| - a), s = -1 (solid) or +1 (cavity) -----------------------
//
// With rho = |x - c| and n = (x - c) / rho: grad varphi = s n and
// hess varphi = s (I - n n^T) / rho (the derivative of the unit vector n).

Ball::Ball(Point centre, double radius, Side side)
    : centre_(std::move(centre)), radius_(radius), side_(side) {
  if (!IsSupportedDim(centre_.size())) {
    throw std::invalid_argument("Ball: the centre has dimension " + std::to_string(centre_.size()) +
                                ", expected 2 or 3");
  }
  if (!centre_.allFinite()) throw std::invalid_argument("Ball: non-finite centre");
  if (!(radius_ > 0.0) || !std::isfinite(radius_)) {
    throw std::invalid_argument("Ball: radius must be positive and finite, got " +
                                std::to_string(radius_));
  }
}

std::string Ball::Describe() const {
  std::ostringstream out;
  const char* shape = dim() == 2 ? "circle" : "sphere";
  if (side_ == Side::kSolid) {
    out << "solid " << shape << " (obstacle inside |x - c| < a)";
  } else {
    out << "cavity " << shape << " (obstacle outside |x - c| > a)";
  }
  out << " with c = " << FormatPoint(centre_) << ", a = " << radius_;
  return out.str();
}

void Ball::Evaluate(const double* x, Order order, ObstacleLocal* out) const {
  const int d = dim();
  const double s = sign();
  double n[3] = {0.0, 0.0, 0.0};
  double rho2 = 0.0;
  for (int c = 0; c < d; ++c) {
    n[c] = x[c] - centre_[c];
    rho2 += n[c] * n[c];
  }
  const double rho = std::sqrt(rho2);
  out->value = s * (rho - radius_);
  if (order == Order::kValue) return;
  if (!(rho > 0.0)) {
    // At the centre the distance has no gradient (every direction is steepest): the first
    // axis, a well-defined unit vector and an element of the generalised gradient there, so
    // that solvers never see NaN. The curvature is unbounded (it grows like 1 / |x - c|): the
    // Hessian is left zero, a finite value, rather than Inf/NaN. Only a node exactly at the
    // centre sees this.
    for (int c = 0; c < d; ++c) out->gradient[c] = c == 0 ? s : 0.0;
    return;
  }
  const double inv_rho = 1.0 / rho;
  for (int c = 0; c < d; ++c) {
    n[c] *= inv_rho;
    out->gradient[c] = s * n[c];
  }
  if (order != Order::kHessian) return;
  const double scale = s * inv_rho;
  for (int a = 0; a < d; ++a) {
    for (int b = 0; b < d; ++b) out->hessian[a][b] = scale * ((a == b ? 1.0 : 0.0) - n[a] * n[b]);
  }
}

// --- Cylinder: varphi(x) = s (rho - a), rho = |P (x - p)|, P = I - e e^T ------------------
//
// With n = P (x - p) / rho, the unit radial direction: grad varphi = s n and
// hess varphi = s (P - n n^T) / rho (the ball's formula restricted to the plane normal to e).

Cylinder::Cylinder(Point point, Point axis, double radius, Side side)
    : point_(std::move(point)), axis_(std::move(axis)), radius_(radius), side_(side) {
  if (point_.size() != 3 || axis_.size() != 3) {
    throw std::invalid_argument("Cylinder: the point and the axis must have 3 components, got " +
                                std::to_string(point_.size()) + " and " +
                                std::to_string(axis_.size()));
  }
  if (!point_.allFinite() || !axis_.allFinite()) {
    throw std::invalid_argument("Cylinder: non-finite point or axis");
  }
  const double length = axis_.norm();
  if (!(length > 0.0)) throw std::invalid_argument("Cylinder: zero axis");
  axis_ /= length;
  if (!(radius_ > 0.0) || !std::isfinite(radius_)) {
    throw std::invalid_argument("Cylinder: radius must be positive and finite, got " +
                                std::to_string(radius_));
  }
}

std::string Cylinder::Describe() const {
  std::ostringstream out;
  out << (side_ == Side::kSolid ? "solid cylinder (obstacle inside rho < a)"
                                : "cavity cylinder (obstacle outside rho > a)")
      << " with axis through p = " << FormatPoint(point_) << " along e = " << FormatPoint(axis_)
      << ", a = " << radius_;
  return out.str();
}

void Cylinder::Evaluate(const double* x, Order order, ObstacleLocal* out) const {
  const double s = side_ == Side::kSolid ? -1.0 : 1.0;
  double along = 0.0;
  for (int c = 0; c < 3; ++c) along += axis_[c] * (x[c] - point_[c]);
  double n[3];
  double rho2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    n[c] = x[c] - point_[c] - along * axis_[c];
    rho2 += n[c] * n[c];
  }
  const double rho = std::sqrt(rho2);
  out->value = s * (rho - radius_);
  if (order == Order::kValue) return;
  if (!(rho > 0.0)) {
    // On the axis the distance has no gradient: a unit vector normal to the axis (an element
    // of the generalised gradient), and a zero (finite) Hessian, as for the ball's centre.
    const int k = std::abs(axis_[0]) < 0.9 ? 0 : 1;
    double m[3] = {0.0, 0.0, 0.0};
    m[k] = 1.0;
    double norm2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      m[c] -= axis_[k] * axis_[c];
      norm2 += m[c] * m[c];
    }
    for (int c = 0; c < 3; ++c) out->gradient[c] = s * m[c] / std::sqrt(norm2);
    return;
  }
  const double inv_rho = 1.0 / rho;
  for (int c = 0; c < 3; ++c) {
    n[c] *= inv_rho;
    out->gradient[c] = s * n[c];
  }
  if (order != Order::kHessian) return;
  const double scale = s * inv_rho;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      out->hessian[a][b] = scale * ((a == b ? 1.0 : 0.0) - axis_[a] * axis_[b] - n[a] * n[b]);
    }
  }
}

}  // namespace cb
