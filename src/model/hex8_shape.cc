#include "model/hex8_shape.h"

#include <Eigen/LU>  // 3 x 3 determinant and inverse
#include <cmath>

namespace cb::hex8 {

bool ShapeGradients(const Mat83& xyz, double xi, double eta, double zeta, Mat83* dn, double* det) {
  Eigen::Matrix<double, 3, 8> dn_nat;
  for (int a = 0; a < 8; ++a) {
    const double sx = 1.0 + xi * kXiNode[a];
    const double sy = 1.0 + eta * kEtaNode[a];
    const double sz = 1.0 + zeta * kZetaNode[a];
    dn_nat(0, a) = 0.125 * kXiNode[a] * sy * sz;
    dn_nat(1, a) = 0.125 * kEtaNode[a] * sx * sz;
    dn_nat(2, a) = 0.125 * kZetaNode[a] * sx * sy;
  }
  // J(i, j) = d X_j / d xi_i; the reference gradients are J^{-1} dN/dxi.
  const Eigen::Matrix3d jac = dn_nat * xyz;
  *det = jac.determinant();
  if (!(*det > 0.0)) return false;
  *dn = (jac.inverse() * dn_nat).transpose();
  return true;
}

void GaussPoint(int gp, double* xi, double* eta, double* zeta) {
  const double g = 1.0 / std::sqrt(3.0);
  *xi = (gp & 1) ? g : -g;
  *eta = (gp & 2) ? g : -g;
  *zeta = (gp & 4) ? g : -g;
}

}  // namespace cb::hex8
