// SolidHex8's stresses at the element centres: the Cauchy stress (linear, or of the
// neo-Hookean law) and its von Mises equivalent, as cell fields for the VTK output.
#include <Eigen/LU>  // 3 x 3 determinant
#include <cmath>

#include "model/displacement_size.h"
#include "model/hex8_shape.h"
#include "model/solid_hex8.h"

namespace cb {
namespace {

// sqrt(3/2 dev(sigma) : dev(sigma)).
double VonMises(const Eigen::Matrix3d& sigma) {
  const Eigen::Matrix3d dev = sigma - (sigma.trace() / 3.0) * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * dev.squaredNorm());
}

}  // namespace

std::vector<CellField> SolidHex8::CellFields(const Vec& u) const {
  CellField tensor{"stress", {}, 9};
  CellField mises{"von_mises_stress", {}};
  for (const Eigen::Matrix3d& sigma : CauchyStress(u)) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) tensor.values.push_back(sigma(i, j));
    }
    mises.values.push_back(VonMises(sigma));
  }
  return {mises, tensor};
}

std::vector<double> SolidHex8::VonMisesStress(const Vec& u) const {
  std::vector<double> out;
  for (const Eigen::Matrix3d& sigma : CauchyStress(u)) out.push_back(VonMises(sigma));
  return out;
}

std::vector<Eigen::Matrix3d> SolidHex8::CauchyStress(const Vec& u) const {
  CheckDisplacementSize(u, num_dofs(), "SolidHex8", "CauchyStress");
  std::vector<Eigen::Matrix3d> out;
  out.reserve(elements_.size());
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const hex8::Mat83 xyz = ElementCoordinates(e);
    hex8::Mat83 dn;
    double det0;
    hex8::ShapeGradients(xyz, 0.0, 0.0, 0.0, &dn, &det0);
    const Eigen::Matrix3d grad = ElementDisplacements(e, u).transpose() * dn;
    Eigen::Matrix3d sigma;
    if (is_linear()) {
      const Eigen::Matrix3d eps = 0.5 * (grad + grad.transpose());
      sigma = lame_lambda_ * eps.trace() * identity + 2.0 * shear_modulus_ * eps;
    } else {
      // Cauchy stress of the neo-Hookean law: (mu (F F^T - I) + lambda ln J I) / J.
      const Eigen::Matrix3d f = identity + grad;
      const double j = f.determinant();
      sigma = (shear_modulus_ * (f * f.transpose() - identity) +
               lame_lambda_ * std::log(j) * identity) /
              j;
    }
    out.push_back(sigma);
  }
  return out;
}

}  // namespace cb
