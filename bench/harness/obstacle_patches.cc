#include "harness/obstacle_patches.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cb::harness {

namespace {

std::vector<Point> ReferencePoints(const ElasticBody& body) {
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(body.num_nodes()));
  for (int n = 0; n < body.num_nodes(); ++n) points.push_back(body.reference(n));
  return points;
}

// The length of each node's shortest edge to another node of a contact pair in an element they
// share (infinity for none): the spacing of the nodes on the contact face, whatever the
// elements' thickness across it.
std::vector<double> ShortestEdges(const ElasticBody& body, const std::vector<Point>& points,
                                  const std::vector<bool>& paired) {
  std::vector<double> shortest(points.size(), std::numeric_limits<double>::infinity());
  for (const std::vector<int>& cell : body.Cells()) {
    for (int a : cell) {
      for (int b : cell) {
        if (a == b || !paired[a] || !paired[b]) continue;
        shortest[a] = std::min(shortest[a], (points[a] - points[b]).norm());
      }
    }
  }
  return shortest;
}

// The box of half-width h around `p` (unused components 0).
Box BoxAt(const Point& p, double h) {
  Box box;
  for (int c = 0; c < static_cast<int>(p.size()) && c < 3; ++c) {
    box.low[c] = p[c] - h;
    box.high[c] = p[c] + h;
  }
  return box;
}

}  // namespace

std::vector<SurfaceGeometry> DrawnObstacles(const BodyContactModel& model) {
  const std::vector<Point> points = ReferencePoints(model.body());
  const Box around = BoxAround(points);
  const auto& obstacles = model.obstacles();
  // The one node an obstacle serves (-1: none or several).
  std::vector<int> only_node(obstacles.size(), -1);
  std::vector<int> pairs(obstacles.size(), 0);
  std::vector<bool> paired(points.size(), false);
  for (const ContactPair& pair : model.pairs()) {
    only_node[pair.obstacle] = pair.node;
    ++pairs[pair.obstacle];
    paired[pair.node] = true;
  }
  const std::vector<double> shortest = ShortestEdges(model.body(), points, paired);
  std::vector<SurfaceGeometry> surfaces;
  surfaces.reserve(obstacles.size());
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const int node = pairs[k] == 1 ? only_node[k] : -1;
    const bool patch = node >= 0 && dynamic_cast<const HalfSpace*>(obstacles[k].get()) != nullptr &&
                       std::isfinite(shortest[node]);
    surfaces.push_back(
        ObstacleSurface(*obstacles[k], patch ? BoxAt(points[node], 0.5 * shortest[node]) : around));
  }
  return surfaces;
}

}  // namespace cb::harness
