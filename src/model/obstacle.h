// Rigid obstacles as signed distances varphi(x), positive INSIDE the obstacle, with
// |grad varphi| = 1 on the surface (docs/method.md section 1). Curved obstacles have a Hessian,
// which is the curvature term sum_p r_p hess phi_p of (29).
#pragma once

#include <memory>
#include <string>

#include "core/types.h"

namespace cb {

// varphi and its derivatives at one point, in fixed-size storage (dim() entries used): the
// model's loops over contact pairs fill one per pair without allocation.
struct ObstacleLocal {
  double value = 0.0;
  double gradient[3] = {0.0, 0.0, 0.0};
  double hessian[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
};

class Obstacle {
 public:
  // How much of ObstacleLocal Evaluate fills.
  enum class Order { kValue, kGradient, kHessian };

  virtual ~Obstacle() = default;
  virtual int dim() const = 0;
  virtual std::string Describe() const = 0;
  // varphi(x) and, up to `order`, its gradient and Hessian (x has dim() entries). One
  // evaluation shares the work between them (a ball's |x - c|), which a Newton iteration on a
  // curved obstacle needs at every pair (residual: value and gradient; Jacobian: gradient and
  // Hessian).
  virtual void Evaluate(const double* x, Order order, ObstacleLocal* out) const = 0;
  // False when the Hessian is identically zero (flat obstacles): no curvature entries needed.
  virtual bool is_curved() const = 0;

  // Evaluate() for one quantity, for callers outside the hot loops.
  double Value(const Point& x) const;
  Point Gradient(const Point& x) const;
  PointMat Hessian(const Point& x) const;
};

// The half-space {x : n.(x - p) > 0} (half-plane in 2-D); `normal` points into the obstacle
// and is normalised here. varphi(x) = n.(x - p).
class HalfSpace final : public Obstacle {
 public:
  HalfSpace(Point point, Point normal);
  int dim() const override { return static_cast<int>(point_.size()); }
  std::string Describe() const override;
  void Evaluate(const double* x, Order order, ObstacleLocal* out) const override;
  bool is_curved() const override { return false; }
  // The definition, for writing the obstacle back out (src/io/).
  const Point& point() const { return point_; }
  const Point& normal() const { return normal_; }

 private:
  Point point_;
  Point normal_;
};

// A circle (2-D) or sphere (3-D) of centre c and radius a. kSolid: the obstacle is the ball,
// varphi = a - |x - c|. kCavity: the obstacle is everything outside the ball (a body inside a
// round hole), varphi = |x - c| - a.
class Ball final : public Obstacle {
 public:
  enum class Side { kSolid, kCavity };
  Ball(Point centre, double radius, Side side);
  int dim() const override { return static_cast<int>(centre_.size()); }
  std::string Describe() const override;
  void Evaluate(const double* x, Order order, ObstacleLocal* out) const override;
  bool is_curved() const override { return true; }
  const Point& centre() const { return centre_; }
  double radius() const { return radius_; }
  Side side() const { return side_; }

 private:
  double sign() const { return side_ == Side::kSolid ? -1.0 : 1.0; }
  Point centre_;
  double radius_;
  Side side_;
};

// A circular cylinder (3-D) of axis through `point` along `axis` (normalised here) and radius a.
// With rho the distance from x to the axis: kSolid, the obstacle is the rod, varphi = a - rho;
// kCavity, the obstacle is everything outside it (a body inside a pipe), varphi = rho - a.
class Cylinder final : public Obstacle {
 public:
  using Side = Ball::Side;
  Cylinder(Point point, Point axis, double radius, Side side);
  int dim() const override { return 3; }
  std::string Describe() const override;
  void Evaluate(const double* x, Order order, ObstacleLocal* out) const override;
  bool is_curved() const override { return true; }
  const Point& point() const { return point_; }
  const Point& axis() const { return axis_; }
  double radius() const { return radius_; }
  Side side() const { return side_; }

 private:
  Point point_;
  Point axis_;
  double radius_;
  Side side_;
};

}  // namespace cb
