// Small problems with closed-form answers, used by the tests (docs/problems.md "Verification").
// Both are trusses with Biot strain, for which N = E A (l - L) / L is exact, so the closed
// forms below hold at any displacement.
#include <cmath>

#include "model/obstacle.h"
#include "model/plane_stress_q4.h"
#include "model/truss.h"
#include "problems/builders.h"

namespace cb {

// --- bar against a wall ---------------------------------------------------------------------
// A bar from (0, 0) (pinned) to (L, 0) (y fixed), pushed in +x by lambda P at its free end
// towards a wall at x = L + gap. Closed form: u = lambda P L / (E A) until u = gap, i.e. up to
// lambda_c = E A gap / (P L); beyond it u = gap and the reaction r = -(lambda P - E A gap / L).

Parameters BarWallDefaults() {
  Parameters p;
  p.DeclareReal("length", 1.0, "L, bar length", 0.0, 1e9, true);
  p.DeclareReal("axial_stiffness", 100.0, "E A", 0.0, 1e30, true);
  p.DeclareReal("gap", 0.01, "initial gap between the free end and the wall", 0.0, 1e9, true);
  p.DeclareReal("load", 1.0, "P, load per unit lambda at the free end", 0.0, 1e30, true);
  p.DeclareReal("arc_length", 0.05, "theta", 0.0, 1e9, true);
  p.DeclareInteger("steps", 60, "arc-length steps", 1, 10000000);
  DeclareScaleParameters(0.01, 1.0, &p);
  return p;
}

Problem BuildBarWall(const Parameters& p) {
  const double length = p.Real("length");
  Mat xy(2, 2);
  xy << 0.0, 0.0, length, 0.0;
  std::vector<TrussMember> members = {{0, 1, p.Real("axial_stiffness"), 1.0}};
  std::vector<bool> fixed = {true, true, false, true};
  auto body = std::make_shared<Truss>(xy, members, fixed);
  Point wall(2), into(2);
  wall << length + p.Real("gap"), 0.0;
  into << 1.0, 0.0;
  std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<HalfSpace>(wall, into)};
  Vec load = Vec::Zero(body->num_dofs());
  Point force(2);
  force << p.Real("load"), 0.0;
  AddNodalForce(body->dofs(), 1, force, &load);

  Problem problem = MakeBodyProblem(body, obstacles, {{1, 0}}, load, p);
  problem.description = "bar pushed against a wall";
  problem.units = "consistent units";
  TraceByArcLength(p, body->dofs().dof(1, 0), "displacement of the free end", &problem);
  return problem;
}

// --- two-bar (von Mises) truss ----------------------------------------------------------------
// Supports at (-b, 0) and (b, 0), apex at (0, h), apex x fixed (so the path stays symmetric)
// unless apex = free, load lambda P downward at the apex. With w = h - v the apex height and l =
// sqrt(b^2 + w^2):
//   lambda(w) = (2 E A / P) (1/l - 1/L) w,            L = sqrt(b^2 + h^2),
// with limit points where l^3 = b^2 L. The obstacle variant puts a floor y < floor_height under
// the apex: once the apex touches it, w stays at floor_height and the floor carries
// r = -(lambda - lambda(floor_height)) P (negative: compression, no adhesion).
// With the apex free to move sideways, the symmetric path has a bifurcation point where the
// sideways stiffness (2 E A / (L l^3)) (b^2 l + (l - L) w^2) vanishes, l^3 = L w^2; it comes
// before the limit point when L > 3^(3/2) b / 2 (a steep truss, e.g. b = 1, h = 3).

namespace {

Parameters TwoBarParameters(bool with_obstacle) {
  Parameters p;
  p.DeclareReal("half_span", 1.0, "b", 0.0, 1e9, true);
  p.DeclareReal("height", 0.5, "h, apex height", 0.0, 1e9, true);
  p.DeclareReal("axial_stiffness", 10.0, "E A of each bar", 0.0, 1e30, true);
  p.DeclareReal("load", 1.0, "P, downward load per unit lambda at the apex", 0.0, 1e30, true);
  p.DeclareChoice("obstacle", with_obstacle ? "floor" : "none", "a floor under the apex",
                  {"none", "floor"});
  p.DeclareReal("floor_height", 0.1, "y of the floor's surface (below the apex)", -1e9, 1e9);
  p.DeclareChoice("apex", "fixed",
                  "fixed: the apex moves vertically only; free: also sideways (a bifurcation "
                  "point on steep trusses)",
                  {"fixed", "free"});
  p.DeclareReal("arc_length", 0.05, "theta", 0.0, 1e9, true);
  p.DeclareInteger("steps", 200, "arc-length steps", 1, 10000000);
  DeclareScaleParameters(0.1, 1.0, &p);
  return p;
}

}  // namespace

Parameters TwoBarDefaults() { return TwoBarParameters(false); }
Parameters TwoBarObstacleDefaults() { return TwoBarParameters(true); }

Problem BuildTwoBar(const Parameters& p) {
  const double b = p.Real("half_span");
  const double h = p.Real("height");
  Mat xy(3, 2);
  xy << -b, 0.0, 0.0, h, b, 0.0;
  const double ea = p.Real("axial_stiffness");
  std::vector<TrussMember> members = {{0, 1, ea, 1.0}, {1, 2, ea, 1.0}};
  std::vector<bool> fixed = {true, true, p.Choice("apex") == "fixed", false, true, true};
  auto body = std::make_shared<Truss>(xy, members, fixed);
  std::vector<std::shared_ptr<const Obstacle>> obstacles;
  std::vector<ContactPair> pairs;
  if (p.Choice("obstacle") == "floor") {
    Point surface(2), down(2);
    surface << 0.0, p.Real("floor_height");
    down << 0.0, -1.0;
    obstacles.push_back(std::make_shared<HalfSpace>(surface, down));
    pairs.push_back({1, 0});
  }
  Vec load = Vec::Zero(body->num_dofs());
  Point force(2);
  force << 0.0, -p.Real("load");
  AddNodalForce(body->dofs(), 1, force, &load);

  Problem problem = MakeBodyProblem(body, obstacles, pairs, load, p);
  problem.description = "von Mises two-bar truss";
  problem.units = "consistent units";
  TraceByArcLength(p, body->dofs().dof(1, 1), "vertical displacement of the apex", &problem);
  return problem;
}

}  // namespace cb
