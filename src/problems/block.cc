// P1 `block` (docs/problems.md; report section 5.1): a square plane-stress body in the corner of a
// rigid wall (x <= 0) and floor (y <= 0), loaded on its right edge, held by contact alone.
#include <cmath>

#include "model/obstacle.h"
#include "model/plane_stress_q4.h"
#include "problems/builders.h"

namespace cb {

Parameters BlockDefaults() {
  Parameters p;
  p.DeclareInteger("n", 50, "elements per side (n x n Q4 mesh)", 1, 2000);
  p.DeclareReal("side", 2.0, "side W of the square body [m]", 0.0, 1e6, true);
  p.DeclareReal("thickness", 0.01, "plane-stress thickness [m]", 0.0, 1e6, true);
  p.DeclareReal("youngs_modulus", 100e6, "E [Pa]", 0.0, 1e30, true);
  p.DeclareReal("poisson_ratio", 0.3, "nu", -1.0, 0.4999999, true);
  p.DeclareReal("traction_x", -0.5e6, "uniform traction on the right edge, x [Pa]", -1e30, 1e30);
  p.DeclareReal("traction_y", -0.5e6, "uniform traction on the right edge, y [Pa]", -1e30, 1e30);
  p.DeclareReal("load", 1.0, "lambda of the single fixed-load solve", -1e30, 1e30);
  // Gaps of the solution are O(1e-2) m and nodal reactions O(1e2) N (docs/method.md section 2).
  DeclareScaleParameters(1e-2, 1e2, &p);
  return p;
}

Problem BuildBlock(const Parameters& p) {
  const int n = p.Integer("n");
  const double side = p.Real("side");
  const double h = side / n;
  const int nodes_per_side = n + 1;
  auto id = [nodes_per_side](int i, int j) { return j * nodes_per_side + i; };

  Mat coordinates(nodes_per_side * nodes_per_side, 2);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) coordinates.row(id(i, j)) << i * h, j * h;
  }
  std::vector<PlaneStressQ4::Element> elements;
  elements.reserve(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      elements.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  PlaneStressMaterial material{p.Real("youngs_modulus"), p.Real("poisson_ratio"),
                               p.Real("thickness")};
  auto body = std::make_shared<PlaneStressQ4>(coordinates, elements, material);

  // Obstacle 0: the wall fills x < 0; obstacle 1: the floor fills y < 0 (normals point in).
  Point origin(2), wall_normal(2), floor_normal(2);
  origin << 0.0, 0.0;
  wall_normal << -1.0, 0.0;
  floor_normal << 0.0, -1.0;
  std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<HalfSpace>(origin, wall_normal),
      std::make_shared<HalfSpace>(origin, floor_normal)};

  // Left-edge nodes against the wall, then bottom-edge nodes against the floor; the corner
  // node is in both, so nc = 2 (n + 1).
  std::vector<ContactPair> pairs;
  for (int j = 0; j <= n; ++j) pairs.push_back({id(0, j), 0});
  for (int i = 0; i <= n; ++i) pairs.push_back({id(i, 0), 1});

  Vec load = Vec::Zero(body->num_dofs());
  Point traction(2);
  traction << p.Real("traction_x"), p.Real("traction_y");
  for (int j = 0; j < n; ++j) body->AddEdgeTraction(id(n, j), id(n, j + 1), traction, &load);

  Problem problem = MakeBodyProblem(body, obstacles, pairs, load, p);
  problem.description =
      "P1 plane-stress block, " + std::to_string(n) + " x " + std::to_string(n) + " Q4, fixed load";
  problem.units = "N, m";
  problem.loading = LoadingKind::kFixedLoad;
  problem.load = p.Real("load");
  problem.steps = 1;
  problem.control_dof = body->dofs().dof(id(n, n), 0);
  problem.control_label = "x-displacement of the top-right corner [m]";
  return problem;
}

}  // namespace cb
