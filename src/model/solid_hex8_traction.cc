// SolidHex8's face tractions: the consistent nodal forces of a uniform dead traction.
#include <Eigen/Geometry>  // cross product
#include <stdexcept>
#include <string>

#include "model/plane_stress_q4.h"  // AddNodalForce
#include "model/solid_hex8.h"

namespace cb {

// A dead traction t on the bilinear face x(xi, eta) = sum_a N_a x_a: the consistent nodal
// force of node a is t integral N_a |x_xi x x_eta| dxi deta (2 x 2 Gauss, exact for a
// parallelogram face).
void SolidHex8::AddFaceTraction(const Face& face, const Point& traction, Vec* load) const {
  const int nodes = num_nodes();
  for (int a = 0; a < 4; ++a) {
    if (face[a] < 0 || face[a] >= nodes) {
      throw std::invalid_argument("SolidHex8::AddFaceTraction: unknown node " +
                                  std::to_string(face[a]));
    }
  }
  if (traction.size() != 3) {
    throw std::invalid_argument("SolidHex8::AddFaceTraction: traction has " +
                                std::to_string(traction.size()) + " components, expected 3");
  }
  constexpr double kXi[4] = {-1, 1, 1, -1};
  constexpr double kEta[4] = {-1, -1, 1, 1};
  const double g = 1.0 / std::sqrt(3.0);
  double weight[4] = {0.0, 0.0, 0.0, 0.0};
  for (int gp = 0; gp < 4; ++gp) {
    const double xi = (gp & 1) ? g : -g;
    const double eta = (gp & 2) ? g : -g;
    Eigen::Vector3d x_xi = Eigen::Vector3d::Zero(), x_eta = Eigen::Vector3d::Zero();
    double n[4];
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d x = coordinates_.row(face[a]).transpose();
      x_xi += 0.25 * kXi[a] * (1.0 + eta * kEta[a]) * x;
      x_eta += 0.25 * kEta[a] * (1.0 + xi * kXi[a]) * x;
      n[a] = 0.25 * (1.0 + xi * kXi[a]) * (1.0 + eta * kEta[a]);
    }
    const double area = x_xi.cross(x_eta).norm();
    for (int a = 0; a < 4; ++a) weight[a] += n[a] * area;
  }
  for (int a = 0; a < 4; ++a) AddNodalForce(dofs_, face[a], weight[a] * traction, load);
}

}  // namespace cb
