// Plane-stress four-node bilinear quadrilaterals (Q4), small strain, 2 x 2 Gauss quadrature.
// Energy u^T K u / 2 with K assembled once.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "model/elastic_body.h"

namespace cb {

struct PlaneStressMaterial {
  double youngs_modulus = 0.0;  // E
  double poisson_ratio = 0.0;   // nu, in (-1, 0.5)
  double thickness = 0.0;
};

class PlaneStressQ4 final : public ElasticBody {
 public:
  using Element = std::array<int, 4>;  // node ids, counter-clockwise

  // `coordinates`: num_nodes x 2. Throws std::invalid_argument for unknown nodes, an element
  // with non-positive Jacobian at a Gauss point (zero area or clockwise), E <= 0,
  // thickness <= 0 or nu outside (-1, 0.5).
  PlaneStressQ4(Mat coordinates, std::vector<Element> elements, const PlaneStressMaterial& material,
                const std::vector<bool>& fixed = {});

  int dim() const override { return 2; }
  int num_nodes() const override { return static_cast<int>(coordinates_.rows()); }
  const DofMap& dofs() const override { return dofs_; }
  Point reference(int node) const override { return coordinates_.row(node).transpose(); }
  bool is_linear() const override { return true; }
  double Energy(const Vec& u) const override;
  void InternalForce(const Vec& u, Vec* force) const override;
  void Stiffness(const Vec& u, SpMat* stiffness) const override;
  // The constant K streamed in its storage order.
  std::vector<std::pair<int, int>> StiffnessEntries() const override;
  void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const override;

  std::vector<std::vector<int>> Cells() const override;
  std::shared_ptr<const ElasticBody> Restricted(const std::vector<int>& elements) const override;
  // The stress at each element's centre: stress_xx, stress_yy, stress_xy and the von Mises
  // stress of the plane stress state, sqrt(sxx^2 - sxx syy + syy^2 + 3 sxy^2).
  std::vector<CellField> CellFields(const Vec& u) const override;
  const std::vector<Element>& elements() const { return elements_; }
  const PlaneStressMaterial& material() const { return material_; }
  const SpMat& stiffness() const { return stiffness_; }

  // Adds the consistent nodal forces of a uniform traction (force per unit area of the edge
  // face, 2 components) on the straight edge from node a to node b: each end node receives
  // traction * thickness * edge length / 2 on its free components.
  void AddEdgeTraction(int node_a, int node_b, const Point& traction, Vec* load) const;

 private:
  Mat coordinates_;
  std::vector<Element> elements_;
  PlaneStressMaterial material_;
  DofMap dofs_;
  SpMat stiffness_;
};

// Adds a point force (dim components) at a node's free components.
void AddNodalForce(const DofMap& dofs, int node, const Point& force, Vec* load);

}  // namespace cb
