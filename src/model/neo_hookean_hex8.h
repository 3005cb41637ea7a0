// The material law of SolidHex8's elements: compressible neo-Hookean in total Lagrangian form,
// its energy, nodal forces and exact tangent per element (docs/problems.md, "Three-dimensional
// solids"). At u = 0 the tangent is the linear isotropic stiffness, so the small-deformation
// body uses it too.
#pragma once

#include <Eigen/Dense>

#include "model/hex8_shape.h"

namespace cb::hex8 {

using Mat24 = Eigen::Matrix<double, 24, 24>;

struct ElementResult {
  double energy = 0.0;
  Mat83 force = Mat83::Zero();    // row a: the force on node a
  Mat24 tangent = Mat24::Zero();  // row 3 a + i, column 3 b + k
};

// Compressible neo-Hookean in total Lagrangian form, F = I + sum_a u_a (x) dN_a:
//   W = mu/2 (F:F - 3) - mu ln J + lambda/2 (ln J)^2,  P = mu (F - F^-T) + lambda ln J F^-T,
//   dP_iJ/dF_kL = mu d_ik d_JL + lambda Finv_Ji Finv_Lk + (mu - lambda ln J) Finv_Jk Finv_Li.
// With the spatial gradients h_a = F^-T dN_a the nodal blocks of the tangent are
//   K_ab,ik = mu d_ik dN_a.dN_b + lambda h_a,i h_b,k + (mu - lambda ln J) h_a,k h_b,i,
// which at u = 0 (F = I) is the linear isotropic elasticity stiffness B^T D B.
// False when J <= 0 at a Gauss point.
bool NeoHookeanElement(const Mat83& xyz, const Mat83& ue, double lambda, double mu,
                       bool want_tangent, ElementResult* out);

}  // namespace cb::hex8
