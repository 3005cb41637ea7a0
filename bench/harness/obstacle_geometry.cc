#include "harness/obstacle_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace cb::harness {

namespace {

constexpr int kCircleSegments = 128;
constexpr int kSphereRings = 16;
constexpr int kSphereSectors = 32;

Point3 Padded(const Point& p) {
  Point3 out{0.0, 0.0, 0.0};
  for (int c = 0; c < static_cast<int>(p.size()) && c < 3; ++c) out[c] = p[c];
  return out;
}

double Dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Point3 Cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Point3 Unit(const Point3& a) {
  const double n = std::sqrt(Dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// p + s t + r q.
Point3 Along(const Point3& p, const Point3& t, double s, const Point3& q = {0, 0, 0},
             double r = 0.0) {
  return {p[0] + s * t[0] + r * q[0], p[1] + s * t[1] + r * q[1], p[2] + s * t[2] + r * q[2]};
}

// Two unit directions perpendicular to the unit vector n and to each other: n x (the axis least
// aligned with n), then n x that (a plane's two in-plane directions, a cylinder's cross-section).
std::pair<Point3, Point3> PerpendicularPair(const Point3& n) {
  const int least = std::abs(n[0]) <= std::abs(n[1]) && std::abs(n[0]) <= std::abs(n[2])
                        ? 0
                        : (std::abs(n[1]) <= std::abs(n[2]) ? 1 : 2);
  Point3 e{0.0, 0.0, 0.0};
  e[least] = 1.0;
  const Point3 t1 = Unit(Cross(n, e));
  return {t1, Cross(n, t1)};
}

// The range of (corner - origin) . direction over the box's corners.
std::pair<double, double> Extent(const Box& box, const Point3& origin, const Point3& direction) {
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < 8; ++k) {
    const Point3 corner{(k & 1) ? box.high[0] : box.low[0], (k & 2) ? box.high[1] : box.low[1],
                        (k & 4) ? box.high[2] : box.low[2]};
    const double s =
        Dot({corner[0] - origin[0], corner[1] - origin[1], corner[2] - origin[2]}, direction);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {lo, hi};
}

SurfaceGeometry HalfSpaceSurface(const HalfSpace& h, const Box& box) {
  const Point3 p = Padded(h.point());
  const Point3 n = Padded(h.normal());
  SurfaceGeometry g;
  if (h.dim() == 2) {
    const Point3 t{-n[1], n[0], 0.0};  // along the boundary line
    const auto [lo, hi] = Extent(box, p, t);
    g.points = {Along(p, t, lo), Along(p, t, hi)};
    g.lines = {{0, 1}};
    return g;
  }
  const auto [t1, t2] = PerpendicularPair(n);
  const auto [lo1, hi1] = Extent(box, p, t1);
  const auto [lo2, hi2] = Extent(box, p, t2);
  g.points = {Along(p, t1, lo1, t2, lo2), Along(p, t1, hi1, t2, lo2), Along(p, t1, hi1, t2, hi2),
              Along(p, t1, lo1, t2, hi2)};
  g.polygons = {{0, 1, 2, 3}};
  return g;
}

SurfaceGeometry BallSurface(const Ball& b) {
  const Point3 c = Padded(b.centre());
  const double a = b.radius();
  SurfaceGeometry g;
  if (b.dim() == 2) {
    std::vector<int> circle;
    for (int k = 0; k < kCircleSegments; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / kCircleSegments;
      g.points.push_back({c[0] + a * std::cos(phi), c[1] + a * std::sin(phi), 0.0});
      circle.push_back(k);
    }
    circle.push_back(0);
    g.lines = {circle};
    return g;
  }
  // Rings of constant polar angle from pole to pole (the poles are points of their own).
  g.points.push_back({c[0], c[1], c[2] + a});
  for (int i = 1; i < kSphereRings; ++i) {
    const double theta = std::numbers::pi * i / kSphereRings;
    for (int j = 0; j < kSphereSectors; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / kSphereSectors;
      g.points.push_back({c[0] + a * std::sin(theta) * std::cos(phi),
                          c[1] + a * std::sin(theta) * std::sin(phi), c[2] + a * std::cos(theta)});
    }
  }
  g.points.push_back({c[0], c[1], c[2] - a});
  const int south = static_cast<int>(g.points.size()) - 1;
  const auto ring = [](int i, int j) { return 1 + (i - 1) * kSphereSectors + j % kSphereSectors; };
  for (int j = 0; j < kSphereSectors; ++j) {
    g.polygons.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < kSphereRings; ++i) {
      g.polygons.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    g.polygons.push_back({ring(kSphereRings - 1, j), south, ring(kSphereRings - 1, j + 1)});
  }
  return g;
}

// A tube of kCircleSegments quadrilaterals around the axis, over the box's extent along it.
SurfaceGeometry CylinderSurface(const Cylinder& c, const Box& box) {
  const Point3 p = Padded(c.point());
  const Point3 axis = Unit(Padded(c.axis()));
  const auto [t1, t2] = PerpendicularPair(axis);
  const auto [lo, hi] = Extent(box, p, axis);
  const double a = c.radius();
  SurfaceGeometry g;
  for (const double s : {lo, hi}) {
    for (int k = 0; k < kCircleSegments; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / kCircleSegments;
      g.points.push_back(Along(Along(p, axis, s), t1, a * std::cos(phi), t2, a * std::sin(phi)));
    }
  }
  for (int k = 0; k < kCircleSegments; ++k) {
    const int next = (k + 1) % kCircleSegments;
    g.polygons.push_back({k, next, kCircleSegments + next, kCircleSegments + k});
  }
  return g;
}

}  // namespace

Box BoxAround(const std::vector<Point>& points) {
  Box box;
  if (points.empty()) return box;
  box.low = box.high = Padded(points.front());
  for (const Point& p : points) {
    const Point3 q = Padded(p);
    for (int c = 0; c < 3; ++c) {
      box.low[c] = std::min(box.low[c], q[c]);
      box.high[c] = std::max(box.high[c], q[c]);
    }
  }
  double diagonal = 0.0, largest = 0.0;
  for (int c = 0; c < 3; ++c) {
    diagonal += (box.high[c] - box.low[c]) * (box.high[c] - box.low[c]);
    largest = std::max({largest, std::abs(box.low[c]), std::abs(box.high[c])});
  }
  const double margin = std::max(
      {0.25 * std::sqrt(diagonal), 1e-3 * largest, largest == 0.0 && diagonal == 0.0 ? 1.0 : 0.0});
  const int dims = static_cast<int>(points.front().size());
  for (int c = 0; c < dims && c < 3; ++c) {
    box.low[c] -= margin;
    box.high[c] += margin;
  }
  return box;
}

SurfaceGeometry ObstacleSurface(const Obstacle& obstacle, const Box& around) {
  if (const auto* h = dynamic_cast<const HalfSpace*>(&obstacle))
    return HalfSpaceSurface(*h, around);
  if (const auto* b = dynamic_cast<const Ball*>(&obstacle)) return BallSurface(*b);
  if (const auto* c = dynamic_cast<const Cylinder*>(&obstacle)) return CylinderSurface(*c, around);
  throw std::invalid_argument("ObstacleSurface: no geometry for the obstacle " +
                              obstacle.Describe());
}

}  // namespace cb::harness
