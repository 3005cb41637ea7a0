// The trilinear shape functions of the eight-node hexahedron (VTK / Gmsh node order) and its
// 2 x 2 x 2 Gauss rule: what SolidHex8, its material law and its stresses evaluate.
#pragma once

#include <Eigen/Dense>

namespace cb::hex8 {

using Mat83 = Eigen::Matrix<double, 8, 3>;

// Natural coordinates of the eight nodes (VTK / Gmsh order).
inline constexpr double kXiNode[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
inline constexpr double kEtaNode[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
inline constexpr double kZetaNode[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

// Reference gradients dN_a/dX (row a) of the trilinear shape functions
// N_a = (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a) / 8 at a natural point, and det J there.
// False when det J <= 0 (a flat or inverted element).
bool ShapeGradients(const Mat83& xyz, double xi, double eta, double zeta, Mat83* dn, double* det);

// The 2 x 2 x 2 Gauss point gp (unit weights) in natural coordinates.
void GaussPoint(int gp, double* xi, double* eta, double* zeta);

}  // namespace cb::hex8
