// Three-dimensional solids of eight-node trilinear hexahedra (H8), 2 x 2 x 2 Gauss quadrature,
// in small deformation (linear isotropic elasticity, energy u^T K u / 2 with K assembled once)
// or large deformation (total Lagrangian, compressible neo-Hookean, exact tangent;
// docs/problems.md, "Three-dimensional solids", says why neo-Hookean).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "model/elastic_body.h"

namespace cb {

struct SolidMaterial {
  double youngs_modulus = 0.0;  // E
  double poisson_ratio = 0.0;   // nu, in (-1, 0.5)
};

enum class SolidKinematics { kSmallStrain, kLargeStrain };

class SolidHex8 final : public ElasticBody {
 public:
  // Node ids in the VTK / Gmsh order: the bottom face 0-1-2-3 counter-clockwise seen from the
  // top face 4-5-6-7, node 4 + k above node k.
  using Element = std::array<int, 8>;
  // A quadrilateral face (4 node ids) for tractions.
  using Face = std::array<int, 4>;

  // `coordinates`: num_nodes x 3. Throws std::invalid_argument for unknown or repeated nodes,
  // an element with non-positive Jacobian at a Gauss point (flat or inverted: wrong node
  // order), E <= 0 or nu outside (-1, 0.5).
  SolidHex8(Mat coordinates, std::vector<Element> elements, const SolidMaterial& material,
            SolidKinematics kinematics, const std::vector<bool>& fixed = {});

  // True when the element's Jacobian is positive at every Gauss point, as the constructor
  // requires (node ids must be valid rows of `coordinates`).
  static bool HasPositiveJacobian(const Mat& coordinates, const Element& element);

  int dim() const override { return 3; }
  int num_nodes() const override { return static_cast<int>(coordinates_.rows()); }
  const DofMap& dofs() const override { return dofs_; }
  Point reference(int node) const override { return coordinates_.row(node).transpose(); }
  bool is_linear() const override { return kinematics_ == SolidKinematics::kSmallStrain; }
  // Large deformation: +infinity once an element is inverted (J <= 0 at a Gauss point), where
  // the neo-Hookean energy is not defined; force and stiffness are then non-finite.
  double Energy(const Vec& u) const override;
  void InternalForce(const Vec& u, Vec* force) const override;
  // Linear: |K| |u|; neo-Hookean: the sum over elements of |f_e| per row.
  void InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const override;
  void Stiffness(const Vec& u, SpMat* stiffness) const override;
  // The pattern's non-zeros in storage order.
  std::vector<std::pair<int, int>> StiffnessEntries() const override;
  void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const override;

  std::vector<std::vector<int>> Cells() const override;
  std::shared_ptr<const ElasticBody> Restricted(const std::vector<int>& elements) const override;
  // "stress": CauchyStress(u), 9 components; "von_mises_stress": VonMisesStress(u) (the names
  // of the 2-D elements' fields).
  std::vector<CellField> CellFields(const Vec& u) const override;
  const std::vector<Element>& elements() const { return elements_; }
  const SolidMaterial& material() const { return material_; }
  SolidKinematics kinematics() const { return kinematics_; }

  // Adds the consistent nodal forces of a uniform dead traction (force per unit reference
  // area, 3 components) on a bilinear quadrilateral face: integral N_a t dA with 2 x 2 Gauss.
  void AddFaceTraction(const Face& face, const Point& traction, Vec* load) const;

  // Per element, the von Mises equivalent of the Cauchy stress at the element centre (small
  // deformation: of the linear stress; the two agree to first order).
  std::vector<double> VonMisesStress(const Vec& u) const;
  // Per element, the Cauchy stress at the element centre, as VonMisesStress takes it.
  std::vector<Eigen::Matrix3d> CauchyStress(const Vec& u) const;

 private:
  // The neo-Hookean elements' forces assembled into *force; with `magnitudes`, their entries'
  // absolute values.
  void AssembleElementForces(const Vec& u, Vec* force, bool magnitudes) const;
  // Element nodal reference coordinates (8 x 3).
  Eigen::Matrix<double, 8, 3> ElementCoordinates(std::size_t element) const;
  // Element nodal displacements (8 x 3), zero on supported components.
  Eigen::Matrix<double, 8, 3> ElementDisplacements(std::size_t element, const Vec& u) const;
  // Adds the element tangents at u into `values` (pattern_'s storage order).
  void AssembleTangent(const Vec& u, double* values) const;

  Mat coordinates_;
  std::vector<Element> elements_;
  SolidMaterial material_;
  SolidKinematics kinematics_;
  double lame_lambda_ = 0.0;
  double shear_modulus_ = 0.0;
  DofMap dofs_;
  SpMat pattern_;  // the stiffness pattern; in small deformation also its values
};

}  // namespace cb
