#include "model/neo_hookean_hex8.h"

#include <Eigen/LU>  // 3 x 3 determinant and inverse
#include <cmath>

namespace cb::hex8 {

bool NeoHookeanElement(const Mat83& xyz, const Mat83& ue, double lambda, double mu,
                       bool want_tangent, ElementResult* out) {
  for (int gp = 0; gp < 8; ++gp) {
    double xi, eta, zeta, det0;
    GaussPoint(gp, &xi, &eta, &zeta);
    Mat83 dn;
    ShapeGradients(xyz, xi, eta, zeta, &dn, &det0);  // checked positive at construction
    const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + ue.transpose() * dn;
    const double j = f.determinant();
    if (!(j > 0.0)) return false;
    const double log_j = std::log(j);
    const Eigen::Matrix3d f_inv = f.inverse();
    out->energy +=
        det0 * (0.5 * mu * (f.squaredNorm() - 3.0) - mu * log_j + 0.5 * lambda * log_j * log_j);
    const Eigen::Matrix3d p = mu * f + (lambda * log_j - mu) * f_inv.transpose();
    out->force.noalias() += det0 * (dn * p.transpose());
    if (!want_tangent) continue;
    const Mat83 h = dn * f_inv;  // row a: h_a = F^-T dN_a
    const double twist = mu - lambda * log_j;
    for (int b = 0; b < 8; ++b) {
      for (int a = 0; a < 8; ++a) {
        const double diagonal = det0 * mu * dn.row(a).dot(dn.row(b));
        for (int k = 0; k < 3; ++k) {
          for (int i = 0; i < 3; ++i) {
            out->tangent(3 * a + i, 3 * b + k) +=
                det0 * (lambda * h(a, i) * h(b, k) + twist * h(a, k) * h(b, i)) +
                (i == k ? diagonal : 0.0);
          }
        }
      }
    }
  }
  // Exactly symmetric in floating point, so that K is (solvers may read one triangle).
  if (want_tangent) out->tangent = 0.5 * (out->tangent + out->tangent.transpose()).eval();
  return true;
}

}  // namespace cb::hex8
