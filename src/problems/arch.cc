// P2 `arch-flat` and P3 `arch-curved` (docs/problems.md; report sections 5.2 and 5.3): a two-layer
// circular arch truss that sags between an upper obstacle (y > 0) and a lower one. Every
// reconstruction choice of docs/problems.md is a parameter here.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "model/obstacle.h"
#include "model/plane_stress_q4.h"
#include "model/truss.h"
#include "problems/builders.h"

namespace cb {

namespace {

Parameters ArchDefaults(double half_span, double half_angle_deg, int upper_nodes, double area_first,
                        double load, const std::string& lower_obstacle, int steps) {
  Parameters p;
  p.DeclareReal("half_span", half_span, "W, half the span between supports (a) and (b) [m]", 0.0,
                1e6, true);
  p.DeclareReal("half_angle_deg", half_angle_deg, "omega, half opening angle of the arch [deg]",
                0.0, 89.0, true);
  p.DeclareInteger("upper_nodes", upper_nodes,
                   "nodes of the upper layer, at equal angles from -omega to +omega", 3, 100000);
  p.DeclareReal("layer_gap", 1.0, "radial distance between the layers [m]", 0.0, 1e6, true);
  p.DeclareReal("area_first", area_first, "cross-section area of member group 1 [m^2]", 0.0, 1e6,
                true);
  p.DeclareReal("area_step", 0.02, "area decrease from one member group to the next [m^2]", -1e6,
                1e6);
  p.DeclareReal("youngs_modulus", 20e6, "E [kN/m^2] (20 GPa)", 0.0, 1e30, true);
  // Reconstruction (docs/problems.md, "The load unit (reconstruction)"): the report prints "5
  // lambda kN" (P2) and "lambda kN" (P3); read in kN the limit points lie some 10^6 arc-length
  // steps away, read in MN (1000 kN) within the report's order of steps. Only the product load x
  // lambda matters: load = 5 (kN) gives the printed reading.
  p.DeclareReal("load", load,
                "load at node (a) in +x per unit lambda [kN] (reconstruction: the report's "
                "load unit read as MN)",
                -1e30, 1e30);
  p.DeclareReal("lower_clearance", 0.1,
                "H2, gap from the lower centre node to the lower obstacle [m]", 0.0, 1e6, true);
  p.DeclareChoice(
      "lower_obstacle", lower_obstacle,
      "flat: half-plane y < -(H1 + H2); cylinder: a rigid disc below the truss, its top "
      "at y = -(H1 + H2) (reconstruction: convex)",
      {"flat", "cylinder"});
  p.DeclareReal("cylinder_radius", 100.0, "radius of the lower cylinder [m]", 0.0, 1e9, true);
  p.DeclareReal("arc_length", 0.1, "theta of (33), ||(du, dlambda)||_2 (du in m)", 0.0, 1e6, true);
  p.DeclareInteger("steps", steps, "arc-length steps of the default path", 1, 10000000);
  // Gaps of the order of the clearance H2, reactions of the order of the load unit (1 MN).
  DeclareScaleParameters(0.1, 1000.0, &p);
  return p;
}

}  // namespace

Parameters ArchFlatDefaults() { return ArchDefaults(7.5, 20.0, 30, 0.33, 5000.0, "flat", 2000); }

Parameters ArchCurvedDefaults() {
  // docs/problems.md: span 75 m read as half-span 37.5 m, which gives H1 = 2.6373 m.
  return ArchDefaults(37.5, 5.0, 70, 0.73, 1000.0, "cylinder", 1604);
}

Problem BuildArch(const Parameters& p) {
  const double omega = p.Real("half_angle_deg") * std::numbers::pi / 180.0;
  const double half_span = p.Real("half_span");
  const double radius = half_span / std::sin(omega);  // R of the upper layer
  const double layer_gap = p.Real("layer_gap");
  const int n_upper = p.Integer("upper_nodes");
  const int panels = n_upper - 1;
  const double panel_angle = 2.0 * omega / panels;
  // The common centre lies above the truss so that the ends of the upper layer are at y = 0.
  const double centre_y = radius * std::cos(omega);
  const double depth = radius * (1.0 - std::cos(omega)) + layer_gap;  // H1

  // Nodes: upper layer 0 .. n_upper-1 (left to right), then the lower layer: left end, the
  // mid-angle node of each panel, right end.
  const int n_lower = panels + 2;
  Mat xy(n_upper + n_lower, 2);
  auto place = [&](int node, double angle, double r) {
    xy.row(node) << r * std::sin(angle), centre_y - r * std::cos(angle);
  };
  for (int i = 0; i < n_upper; ++i) place(i, -omega + i * panel_angle, radius);
  const int lower0 = n_upper;
  place(lower0, -omega, radius + layer_gap);
  for (int k = 0; k < panels; ++k) {
    place(lower0 + 1 + k, -omega + (k + 0.5) * panel_angle, radius + layer_gap);
  }
  place(lower0 + n_lower - 1, omega, radius + layer_gap);

  // Members: upper chord, lower chord, two diagonals per panel, two end posts.
  std::vector<std::pair<int, int>> links;
  for (int i = 0; i + 1 < n_upper; ++i) links.emplace_back(i, i + 1);
  for (int k = 0; k + 1 < n_lower; ++k) links.emplace_back(lower0 + k, lower0 + k + 1);
  for (int k = 0; k < panels; ++k) {
    links.emplace_back(lower0 + 1 + k, k);
    links.emplace_back(lower0 + 1 + k, k + 1);
  }
  links.emplace_back(lower0, 0);
  links.emplace_back(lower0 + n_lower - 1, n_upper - 1);

  // Cross-section groups: a member's group is 1 + floor(angular distance of its midpoint from
  // the nearer end / panel angle). Members whose midpoint lies on a panel boundary (lower chord)
  // sit exactly on an integer; the small relative tolerance makes that integer win over
  // rounding.
  const double area_first = p.Real("area_first");
  const double area_step = p.Real("area_step");
  std::vector<TrussMember> members;
  for (const auto& [i, j] : links) {
    const double mx = 0.5 * (xy(i, 0) + xy(j, 0));
    const double my = 0.5 * (xy(i, 1) + xy(j, 1));
    const double angle = std::atan2(mx, centre_y - my);
    const double distance = omega - std::abs(angle);
    const int group = 1 + static_cast<int>(std::floor(distance / panel_angle + 1e-9));
    const double area = area_first - (group - 1) * area_step;
    if (!(area > 0.0)) {
      throw std::invalid_argument(
          "area_first - (group - 1) * area_step is not positive for group " +
          std::to_string(group));
    }
    members.push_back({i, j, p.Real("youngs_modulus"), area});
  }

  // Supports: (a) = left end of the upper layer, y fixed (roller); (b) = right end, pinned.
  const int node_a = 0;
  const int node_b = n_upper - 1;
  std::vector<bool> fixed(2 * xy.rows(), false);
  fixed[2 * node_a + 1] = true;
  fixed[2 * node_b] = true;
  fixed[2 * node_b + 1] = true;
  auto body = std::make_shared<Truss>(xy, members, fixed);

  // Obstacle 0: the upper one fills y > 0. Obstacle 1: the lower one, top at y = -(H1 + H2).
  const double lower_top = -(depth + p.Real("lower_clearance"));
  Point origin(2), up(2);
  origin << 0.0, 0.0;
  up << 0.0, 1.0;
  std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<HalfSpace>(origin, up)};
  if (p.Choice("lower_obstacle") == "flat") {
    Point top(2), down(2);
    top << 0.0, lower_top;
    down << 0.0, -1.0;
    obstacles.push_back(std::make_shared<HalfSpace>(top, down));
  } else {
    const double a = p.Real("cylinder_radius");
    Point centre(2);
    centre << 0.0, lower_top - a;
    obstacles.push_back(std::make_shared<Ball>(centre, a, Ball::Side::kSolid));
  }

  // Pairs: the upper nodes other than (a), (b) against the upper obstacle, then every lower
  // node against the upper and against the lower obstacle: nc = (n_upper - 2) + 2 n_lower.
  std::vector<ContactPair> pairs;
  for (int i = 1; i + 1 < n_upper; ++i) pairs.push_back({i, 0});
  for (int k = 0; k < n_lower; ++k) pairs.push_back({lower0 + k, 0});
  for (int k = 0; k < n_lower; ++k) pairs.push_back({lower0 + k, 1});

  Vec load = Vec::Zero(body->num_dofs());
  Point force(2);
  force << p.Real("load"), 0.0;
  AddNodalForce(body->dofs(), node_a, force, &load);

  Problem problem = MakeBodyProblem(body, obstacles, pairs, load, p);
  const bool flat = p.Choice("lower_obstacle") == "flat";
  problem.description = std::string(flat ? "P2" : "P3") + " two-layer arch truss, " +
                        std::to_string(xy.rows()) + " nodes, " + std::to_string(members.size()) +
                        " members";
  problem.units = "kN, m";
  problem.loading = LoadingKind::kArcLength;
  problem.arc_length = p.Real("arc_length");
  problem.steps = p.Integer("steps");
  problem.control_dof = body->dofs().dof(node_a, 0);
  problem.control_label = "x-displacement of node (a) [m]";
  return problem;
}

}  // namespace cb
