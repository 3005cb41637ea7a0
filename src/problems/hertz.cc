// `hertz-3d` (docs/problems.md): an elastic block pressed onto a rigid sphere in small
// deformation, compared with Hertz's closed form. A quarter of the block, [0, L]^2 x [0, H],
// with symmetry supports on x = 0 and y = 0, on a mesh graded toward the contact point at the
// origin; uniform pressure on the top face; the bottom face's nodes are the contact candidates.
#include "problems/hertz.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "model/obstacle.h"
#include "model/solid_hex8.h"
#include "problems/box_mesh.h"
#include "problems/builders.h"

namespace cb {

Parameters HertzDefaults() {
  Parameters p;
  p.DeclareInteger("n", 16, "hexahedra along x and along y of the quarter block", 1, 1000);
  p.DeclareInteger("nz", 16, "hexahedra along z (the height)", 1, 1000);
  p.DeclareReal("grading", 2.0,
                "g >= 1: node i of n along each axis at (i / n)^g of the side, cells smallest "
                "at the contact point",
                1.0, 10.0);
  p.DeclareReal("half_width", 10.0, "L, half the block's width (the quarter is L x L) [mm]", 0.0,
                1e9, true);
  p.DeclareReal("height", 10.0, "H, the block's height [mm]", 0.0, 1e9, true);
  p.DeclareReal("youngs_modulus", 1000.0, "E of the block [N/mm^2]", 0.0, 1e30, true);
  p.DeclareReal("poisson_ratio", 0.3, "nu of the block", -1.0, 0.4999999, true);
  p.DeclareReal("sphere_radius", 50.0, "R of the rigid sphere [mm]", 0.0, 1e9, true);
  p.DeclareReal("force", 30.0, "P, the total force on the whole block per unit lambda [N]", 0.0,
                1e30, true);
  p.DeclareChoice("obstacle", "paraboloid",
                  "paraboloid: Hertz's gap z + rho^2 / (2 R) along z at each node (the theory's "
                  "assumption; a linear model); sphere: the exact rigid sphere (curved)",
                  {"paraboloid", "sphere"});
  p.DeclareReal("load", 1.0, "lambda of the single fixed-load solve", -1e30, 1e30);
  // L: the gaps of the bottom face, rho^2 / (2 R) = 0 ... 2 mm, are O(1-20) L, not O(100) L as
  // with the approach a^2 / R ~ 0.02 mm: psi(g/L, -r/R, rho) then weighs the open pairs' rows as
  // the closed ones', and the cold start (every pair at g = L, r = R; docs/method.md section 4)
  // no longer stalls on a stationary point of the merit (8^3 with the sphere). R: nodal
  // reactions ~ 0.1 N.
  DeclareScaleParameters(1e-1, 1e-1, &p);
  return p;
}

Problem BuildHertz(const Parameters& p) {
  const int n = p.Integer("n");
  const int nz = p.Integer("nz");
  const double g = p.Real("grading");
  const double half_width = p.Real("half_width");
  const BoxMesh mesh =
      MakeBoxMesh({{n, n, nz}, {half_width, half_width, p.Real("height")}, {g, g, g}});

  // Symmetry: u_x = 0 on x = 0, u_y = 0 on y = 0.
  std::vector<bool> fixed(3 * mesh.coordinates.rows(), false);
  for (int node : mesh.FaceNodes(0, 0)) fixed[3 * node + 0] = true;
  for (int node : mesh.FaceNodes(1, 0)) fixed[3 * node + 1] = true;
  const SolidMaterial material{p.Real("youngs_modulus"), p.Real("poisson_ratio")};
  auto body = std::make_shared<SolidHex8>(mesh.coordinates, mesh.elements, material,
                                          SolidKinematics::kSmallStrain, fixed);

  // The sphere touches the bottom face at the origin. The paraboloid reading gives node p its
  // own half-space z < -rho_p^2 / (2 R) (normal -z): Hertz's linearised gap, affine in u.
  const double radius = p.Real("sphere_radius");
  std::vector<std::shared_ptr<const Obstacle>> obstacles;
  std::vector<ContactPair> pairs;
  Point down(3);
  down << 0.0, 0.0, -1.0;
  const bool paraboloid = p.Choice("obstacle") == "paraboloid";
  if (!paraboloid) {
    Point centre(3);
    centre << 0.0, 0.0, -radius;
    obstacles.push_back(std::make_shared<Ball>(centre, radius, Ball::Side::kSolid));
  }
  for (int node : mesh.FaceNodes(2, 0)) {
    if (paraboloid) {
      const double x = mesh.coordinates(node, 0), y = mesh.coordinates(node, 1);
      Point top(3);
      top << 0.0, 0.0, -(x * x + y * y) / (2.0 * radius);
      pairs.push_back({node, static_cast<int>(obstacles.size())});
      obstacles.push_back(std::make_shared<HalfSpace>(top, down));
    } else {
      pairs.push_back({node, 0});
    }
  }

  // A quarter of the force P as a uniform pressure on the top of the quarter.
  Vec load = Vec::Zero(body->num_dofs());
  Point traction(3);
  traction << 0.0, 0.0, -p.Real("force") / (4.0 * half_width * half_width);
  for (const auto& face : mesh.Faces(2, nz)) body->AddFaceTraction(face, traction, &load);

  Problem problem = MakeBodyProblem(body, obstacles, pairs, load, p);
  problem.description = "hertz-3d: quarter elastic block on a rigid sphere, " + std::to_string(n) +
                        " x " + std::to_string(n) + " x " + std::to_string(nz) +
                        " hexahedra, fixed load";
  problem.units = "N, mm";
  problem.loading = LoadingKind::kFixedLoad;
  problem.load = p.Real("load");
  problem.steps = 1;
  problem.control_dof = body->dofs().dof(mesh.node(0, 0, 0), 2);
  problem.control_label = "z-displacement of the contact point [mm]";
  return problem;
}

HertzContact HertzClosedForm(double force, double sphere_radius, double youngs_modulus,
                             double poisson_ratio) {
  const double e_star = youngs_modulus / (1.0 - poisson_ratio * poisson_ratio);
  HertzContact out;
  out.radius = std::cbrt(3.0 * force * sphere_radius / (4.0 * e_star));
  out.peak_pressure = 3.0 * force / (2.0 * std::numbers::pi * out.radius * out.radius);
  return out;
}

HertzContact MeasureHertzContact(const Problem& problem, const Vec& r) {
  if (!problem.body || r.size() != problem.body->num_pairs()) {
    throw std::invalid_argument("MeasureHertzContact: r does not match the problem's pairs");
  }
  const ElasticBody& body = problem.body->body();
  double total = 0.0, second_moment = 0.0, at_origin = 0.0;
  double first_x = 0.0, first_y = 0.0;  // the first cell's sides: the smallest positive x, y
  for (int q = 0; q < problem.body->num_pairs(); ++q) {
    const Point x = body.reference(problem.body->pairs()[q].node);
    const double force = -r[q];  // r <= 0 presses the body
    total += force;
    second_moment += force * (x[0] * x[0] + x[1] * x[1]);
    if (x[0] == 0.0 && x[1] == 0.0) at_origin = force;
    if (x[0] > 0.0 && (first_x == 0.0 || x[0] < first_x)) first_x = x[0];
    if (x[1] > 0.0 && (first_y == 0.0 || x[1] < first_y)) first_y = x[1];
  }
  HertzContact out;
  out.radius = total > 0.0 ? std::sqrt(2.5 * second_moment / total) : 0.0;
  out.peak_pressure = first_x > 0.0 && first_y > 0.0 ? at_origin / (0.25 * first_x * first_y) : 0.0;
  return out;
}

}  // namespace cb
