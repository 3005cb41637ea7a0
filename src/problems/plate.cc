// `plate-3d` (docs/problems.md): a thick plate of neo-Hookean hexahedra, clamped on two opposite
// ends, pressed by a uniform pressure onto a rigid cylinder below its middle; traced by arc
// length while the contact spreads node row by node row (every row entering contact is a kink).
#include "model/obstacle.h"
#include "model/solid_hex8.h"
#include "problems/box_mesh.h"
#include "problems/builders.h"

namespace cb {

Parameters PlateDefaults() {
  Parameters p;
  p.DeclareInteger("nx", 16, "hexahedra along the span x", 2, 1000);
  p.DeclareInteger("ny", 2, "hexahedra across the width y", 1, 1000);
  p.DeclareInteger("nz", 2, "hexahedra through the thickness z", 1, 1000);
  p.DeclareReal("span", 8.0, "span between the clamped ends [m]", 0.0, 1e9, true);
  p.DeclareReal("width", 1.0, "width [m]", 0.0, 1e9, true);
  p.DeclareReal("thickness", 0.4, "thickness [m]", 0.0, 1e9, true);
  p.DeclareReal("youngs_modulus", 1000.0, "E [kN/m^2]", 0.0, 1e30, true);
  p.DeclareReal("poisson_ratio", 0.3, "nu", -1.0, 0.4999999, true);
  p.DeclareReal("cylinder_radius", 10.0, "radius of the rigid cylinder below the middle [m]", 0.0,
                1e9, true);
  p.DeclareReal("clearance", 0.2, "gap between the plate's bottom and the cylinder's top [m]", 0.0,
                1e9, true);
  p.DeclareReal("pressure", 0.5, "pressure on the top face per unit lambda [kN/m^2]", -1e30, 1e30);
  p.DeclareReal("arc_length", 0.1, "theta of (33), ||(du, dlambda)||_2 (du in m)", 0.0, 1e6, true);
  p.DeclareInteger("steps", 200, "arc-length steps of the default path", 1, 10000000);
  // Gaps of the order of the clearance, nodal reactions of the order of the nodal load.
  DeclareScaleParameters(0.1, 0.01, &p);
  return p;
}

Problem BuildPlate(const Parameters& p) {
  const int nx = p.Integer("nx"), ny = p.Integer("ny"), nz = p.Integer("nz");
  const double span = p.Real("span");
  const BoxMesh mesh =
      MakeBoxMesh({{nx, ny, nz}, {span, p.Real("width"), p.Real("thickness")}, {1.0, 1.0, 1.0}});
  std::vector<bool> fixed(3 * mesh.coordinates.rows(), false);
  for (int index : {0, nx}) {
    for (int node : mesh.FaceNodes(0, index)) {
      for (int c = 0; c < 3; ++c) fixed[3 * node + c] = true;
    }
  }
  const SolidMaterial material{p.Real("youngs_modulus"), p.Real("poisson_ratio")};
  auto body = std::make_shared<SolidHex8>(mesh.coordinates, mesh.elements, material,
                                          SolidKinematics::kLargeStrain, fixed);

  // The cylinder's axis runs along y under the middle of the span.
  const double radius = p.Real("cylinder_radius");
  Point point(3), axis(3);
  point << 0.5 * span, 0.0, -p.Real("clearance") - radius;
  axis << 0.0, 1.0, 0.0;
  std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<Cylinder>(point, axis, radius, Cylinder::Side::kSolid)};
  std::vector<ContactPair> pairs;
  for (int node : mesh.FaceNodes(2, 0)) {
    if (!fixed[3 * node]) pairs.push_back({node, 0});
  }

  Vec load = Vec::Zero(body->num_dofs());
  Point traction(3);
  traction << 0.0, 0.0, -p.Real("pressure");
  for (const auto& face : mesh.Faces(2, nz)) body->AddFaceTraction(face, traction, &load);

  Problem problem = MakeBodyProblem(body, obstacles, pairs, load, p);
  problem.description = "plate-3d: neo-Hookean plate pressed onto a cylinder, " +
                        std::to_string(nx) + " x " + std::to_string(ny) + " x " +
                        std::to_string(nz) + " hexahedra, arc length";
  problem.units = "kN, m";
  TraceByArcLength(p, body->dofs().dof(mesh.node(nx / 2, 0, 0), 2),
                   "z-displacement of the bottom mid-span node [m]", &problem);
  return problem;
}

}  // namespace cb
