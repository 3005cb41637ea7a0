// P2 `arch-flat` and P3 `arch-curved` (docs/problems.md; report sections 5.2 and 5.3): a two-layer
// circular arch truss that sags between an upper obstacle (y > 0) and a lower one. Every
// reconstruction choice of docs/problems.md is a parameter here.
#include <cmath>
#include <numbers>

#include "model/obstacle.h"
#include "model/plane_stress_q4.h"
#include "model/truss.h"
#include "problems/arch_areas.h"
#include "problems/arch_layout.h"
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
  // The readings of the report's figure (docs/problems.md, "Other readings"); the defaults are
  // the one that gives the report's d, nc and areas.
  p.DeclareChoice("topology", "warren",
                  "reconstruction: warren = a lower node at each panel's mid-angle, two diagonals "
                  "from it; pratt, howe, x-braced = a lower node under each upper node, verticals, "
                  "diagonals falling towards the centre / rising towards it / both",
                  ArchTopologyNames());
  p.DeclareChoice("area_groups", "from-supports",
                  "reconstruction: the member groups (1), (2), ... of area_first, area_first - "
                  "area_step, ...: panels counted from-supports or from-centre, uniform (all "
                  "area_first), by-member-type (upper chord, lower chord, diagonals, posts)",
                  AreaGroupsNames());
  p.DeclareReal("centre_area", 0.0,
                "area of the centre panel's members (largest group counted from the supports), "
                "overriding area_groups; 0 keeps the rule's [m^2]",
                0.0, 1e6);
  p.DeclareChoice("lower_placement", "radial",
                  "reconstruction: radial = lower layer on radius R + layer_gap about the common "
                  "centre; vertical = layer_gap straight below the upper circle (same H1)",
                  LowerPlacementNames());
  return p;
}

}  // namespace

Parameters ArchFlatDefaults() { return ArchDefaults(7.5, 20.0, 30, 0.33, 5000.0, "flat", 2000); }

Parameters ArchCurvedDefaults() {
  // docs/problems.md: span 75 m read as half-span 37.5 m, which gives H1 = 2.6373 m.
  return ArchDefaults(37.5, 5.0, 70, 0.73, 1000.0, "cylinder", 1604);
}

Problem BuildArch(const Parameters& p) {
  ArchCircle circle;
  circle.omega = p.Real("half_angle_deg") * std::numbers::pi / 180.0;
  circle.radius = p.Real("half_span") / std::sin(circle.omega);  // R of the upper layer
  circle.layer_gap = p.Real("layer_gap");
  circle.upper_nodes = p.Integer("upper_nodes");
  // The common centre lies above the truss so that the ends of the upper layer are at y = 0.
  circle.centre_y = circle.radius * std::cos(circle.omega);
  const double depth = circle.radius * (1.0 - std::cos(circle.omega)) + circle.layer_gap;  // H1

  const ArchLayout layout = LayOutArch(circle, ArchTopologyNamed(p.Choice("topology")),
                                       LowerPlacementNamed(p.Choice("lower_placement")));
  const AreaRule rule{AreaGroupsNamed(p.Choice("area_groups")), p.Real("area_first"),
                      p.Real("area_step"), p.Real("centre_area")};
  const std::vector<double> areas = MemberAreas(layout, circle, rule);
  std::vector<TrussMember> members;
  for (std::size_t m = 0; m < layout.links.size(); ++m) {
    members.push_back(
        {layout.links[m].first, layout.links[m].second, p.Real("youngs_modulus"), areas[m]});
  }
  const Mat& xy = layout.xy;
  const int n_upper = circle.upper_nodes;
  const int lower0 = layout.first_lower;
  const int n_lower = layout.lower_nodes;

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
  TraceByArcLength(p, body->dofs().dof(node_a, 0), "x-displacement of node (a) [m]", &problem);
  return problem;
}

}  // namespace cb
