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

}  // namespace

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
  // Normalised so that varphi is a signed distance (|grad varphi| = 1, METHOD.md section 1).
  normal_ /= length;
}

std::string HalfSpace::Describe() const {
  return std::string(dim() == 2 ? "half-plane" : "half-space") +
         " n.(x - p) > 0 with p = " + FormatPoint(point_) + ", n = " + FormatPoint(normal_);
}

double HalfSpace::Value(const Point& x) const { return normal_.dot(x - point_); }

Point HalfSpace::Gradient(const Point& /*x*/) const { return normal_; }

PointMat HalfSpace::Hessian(const Point& /*x*/) const { return PointMat::Zero(dim(), dim()); }

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

double Ball::Value(const Point& x) const { return sign() * ((x - centre_).norm() - radius_); }

Point Ball::Gradient(const Point& x) const {
  Point n = x - centre_;
  const double rho = n.norm();
  if (!(rho > 0.0)) {
    // At the centre the distance has no gradient (every direction is steepest). Return the
    // first axis, a well-defined unit vector, so that solvers never see NaN; any unit vector
    // is an element of the generalised gradient there.
    Point e = Point::Zero(dim());
    e[0] = sign();
    return e;
  }
  n /= rho;
  return sign() * n;
}

PointMat Ball::Hessian(const Point& x) const {
  Point n = x - centre_;
  const double rho = n.norm();
  // At the centre the curvature is unbounded (it grows like 1 / |x - c|); return zero, a
  // finite value, rather than Inf/NaN. Only a node exactly at the centre sees this.
  if (!(rho > 0.0)) return PointMat::Zero(dim(), dim());
  n /= rho;
  PointMat h = PointMat::Identity(dim(), dim());
  h.noalias() -= n * n.transpose();
  h *= sign() / rho;
  return h;
}

}  // namespace cb
