// The obstacles as geometry to draw: a finite piece of each surface near the body, as points
// with polylines (2-D: a half-plane's boundary line, a circle) or polygons (3-D: a half-space's
// boundary plane, a sphere). The obstacle is a signed distance (model/obstacle.h); what is drawn
// is its zero level set, clipped around the body.
#pragma once

#include <array>
#include <vector>

#include "model/obstacle.h"

namespace cb::harness {

using Point3 = std::array<double, 3>;

struct SurfaceGeometry {
  std::vector<Point3> points;
  std::vector<std::vector<int>> lines;     // open polylines; a closed one repeats its start
  std::vector<std::vector<int>> polygons;  // 3-D faces
};

// An axis-aligned box (unused components 0).
struct Box {
  Point3 low{0.0, 0.0, 0.0};
  Point3 high{0.0, 0.0, 0.0};
};

// The box of `points` (dim components each), enlarged on every side by a quarter of its
// diagonal (at least 1e-3 of the largest coordinate, and 1 for a single point at the origin),
// so that a surface drawn over it extends past the body.
Box BoxAround(const std::vector<Point>& points);

// The zero level set of `obstacle` near `around`: a half-space's boundary clipped to the box's
// projection on it, a ball's whole surface (a circle of 128 segments; a sphere of 16 x 32
// facets). Throws std::invalid_argument for an obstacle of another kind.
SurfaceGeometry ObstacleSurface(const Obstacle& obstacle, const Box& around);

}  // namespace cb::harness
