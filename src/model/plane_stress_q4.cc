#include "model/plane_stress_q4.h"

#include <Eigen/LU>  // 2 x 2 determinant and inverse
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "model/continuum_inputs.h"
#include "model/displacement_size.h"
#include "model/element_pattern.h"

namespace cb {
namespace {

using Mat8 = Eigen::Matrix<double, 8, 8>;
using Mat38 = Eigen::Matrix<double, 3, 8>;

// Natural coordinates of the four nodes, counter-clockwise from (-1, -1).
constexpr double kXiNode[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kEtaNode[4] = {-1.0, -1.0, 1.0, 1.0};

[[noreturn]] void ThrowElement(std::size_t element, const std::string& reason) {
  throw std::invalid_argument("PlaneStressQ4: element " + std::to_string(element) + " " + reason);
}

void CheckSize(const Vec& u, int num_dofs, const char* what) {
  CheckDisplacementSize(u, num_dofs, "PlaneStressQ4", what);
}

// Plane-stress elasticity times thickness: t E / (1 - nu^2) [[1, nu, 0], [nu, 1, 0],
// [0, 0, (1 - nu) / 2]], acting on (eps_xx, eps_yy, gamma_xy).
Eigen::Matrix3d ElasticityMatrix(const PlaneStressMaterial& m) {
  const double nu = m.poisson_ratio;
  const double c = m.thickness * m.youngs_modulus / (1.0 - nu * nu);
  Eigen::Matrix3d d;
  d << c, c * nu, 0.0, c * nu, c, 0.0, 0.0, 0.0, c * (1.0 - nu) / 2.0;
  return d;
}

// The strain-displacement matrix B (eps = B u_e, eps = (eps_xx, eps_yy, gamma_xy)) of the
// bilinear isoparametric quadrilateral with nodal coordinates `xy` (row a = node a) at the
// natural coordinates (xi, eta), and det J there. Returns false if det J <= 0 (a degenerate or
// clockwise element).
bool StrainDisplacement(const Eigen::Matrix<double, 4, 2>& xy, double xi, double eta, Mat38* b,
                        double* det) {
  // Derivatives of N_a = (1 + xi xi_a)(1 + eta eta_a) / 4 in natural coordinates.
  Eigen::Matrix<double, 2, 4> dn_nat;
  for (int a = 0; a < 4; ++a) {
    dn_nat(0, a) = 0.25 * kXiNode[a] * (1.0 + eta * kEtaNode[a]);
    dn_nat(1, a) = 0.25 * kEtaNode[a] * (1.0 + xi * kXiNode[a]);
  }
  // J(i, j) = d x_j / d xi_i; the physical derivatives are J^{-1} dN/dxi.
  const Eigen::Matrix2d jac = dn_nat * xy;
  *det = jac.determinant();
  if (!(*det > 0.0)) return false;
  const Eigen::Matrix<double, 2, 4> dn = jac.inverse() * dn_nat;
  b->setZero();
  for (int a = 0; a < 4; ++a) {
    (*b)(0, 2 * a) = dn(0, a);
    (*b)(1, 2 * a + 1) = dn(1, a);
    (*b)(2, 2 * a) = dn(1, a);
    (*b)(2, 2 * a + 1) = dn(0, a);
  }
  return true;
}

// Element stiffness K_e = sum_gauss B^T D B det J (2 x 2 Gauss, unit weights) of the bilinear
// isoparametric quadrilateral with nodal coordinates `xy` (row a = node a). Returns false if
// det J <= 0 at a Gauss point (degenerate or clockwise element).
bool ElementStiffness(const Eigen::Matrix<double, 4, 2>& xy, const Eigen::Matrix3d& d, Mat8* ke) {
  const double g = 1.0 / std::sqrt(3.0);
  ke->setZero();
  for (int gp = 0; gp < 4; ++gp) {
    const double xi = (gp == 0 || gp == 3) ? -g : g;
    const double eta = gp < 2 ? -g : g;
    Mat38 b;
    double det = 0.0;
    if (!StrainDisplacement(xy, xi, eta, &b, &det)) return false;
    ke->noalias() += det * (b.transpose() * (d * b));
  }
  // Exactly symmetric in floating point, so that K is (solvers may read one triangle).
  *ke = 0.5 * (*ke + ke->transpose()).eval();
  return true;
}

// The inputs the constructor refuses: coordinates not n x 2 or not finite, a material out of
// range, a `fixed` of the wrong size.
void CheckInputs(const Mat& coordinates, const PlaneStressMaterial& material,
                 const std::vector<bool>& fixed) {
  CheckNodeCoordinates("PlaneStressQ4", coordinates, 2);
  CheckYoungsModulus("PlaneStressQ4", material.youngs_modulus);
  if (!(material.thickness > 0.0) || !std::isfinite(material.thickness)) {
    throw std::invalid_argument("PlaneStressQ4: thickness must be positive, got " +
                                std::to_string(material.thickness));
  }
  CheckPoissonRatio("PlaneStressQ4", material.poisson_ratio);
  CheckFixedSize("PlaneStressQ4", fixed, static_cast<int>(coordinates.rows()), 2);
}

// Every element names four distinct known nodes.
void CheckElements(const std::vector<PlaneStressQ4::Element>& elements, int nodes) {
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const PlaneStressQ4::Element& el = elements[e];
    for (int a = 0; a < 4; ++a) {
      if (el[a] < 0 || el[a] >= nodes) {
        ThrowElement(e, "names an unknown node " + std::to_string(el[a]) + " (the mesh has " +
                            std::to_string(nodes) + " nodes)");
      }
      for (int b = 0; b < a; ++b) {
        if (el[a] == el[b]) ThrowElement(e, "repeats node " + std::to_string(el[a]));
      }
    }
  }
}

// Element loop: scatter-add K_e into the slots of `stiffness`'s pattern found by binary search
// in each column.
void AssembleStiffness(const Mat& coordinates, const std::vector<PlaneStressQ4::Element>& elements,
                       const PlaneStressMaterial& material, const DofMap& dofs, SpMat* stiffness) {
  const Eigen::Matrix3d dmat = ElasticityMatrix(material);
  const int* col_start = stiffness->outerIndexPtr();
  const int* rows = stiffness->innerIndexPtr();
  double* values = stiffness->valuePtr();
  Mat8 ke;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const PlaneStressQ4::Element& el = elements[e];
    Eigen::Matrix<double, 4, 2> xy;
    int dof[8];
    for (int a = 0; a < 4; ++a) {
      xy.row(a) = coordinates.row(el[a]);
      dof[2 * a] = dofs.dof(el[a], 0);
      dof[2 * a + 1] = dofs.dof(el[a], 1);
    }
    if (!ElementStiffness(xy, dmat, &ke)) {
      ThrowElement(e, "has non-positive area or clockwise node order");
    }
    for (int b = 0; b < 8; ++b) {
      const int j = dof[b];
      if (j < 0) continue;
      const int* first = rows + col_start[j];
      const int* last = rows + col_start[j + 1];
      for (int a = 0; a < 8; ++a) {
        if (dof[a] < 0) continue;
        values[std::lower_bound(first, last, dof[a]) - rows] += ke(a, b);
      }
    }
  }
}

}  // namespace

PlaneStressQ4::PlaneStressQ4(Mat coordinates, std::vector<Element> elements,
                             const PlaneStressMaterial& material, const std::vector<bool>& fixed)
    : coordinates_(std::move(coordinates)), elements_(std::move(elements)), material_(material) {
  CheckInputs(coordinates_, material_, fixed);
  dofs_ = DofMap(num_nodes(), 2, fixed);
  CheckElements(elements_, num_nodes());
  stiffness_ = ElementStiffnessPattern(dofs_, elements_);
  AssembleStiffness(coordinates_, elements_, material_, dofs_, &stiffness_);
}

double PlaneStressQ4::Energy(const Vec& u) const {
  CheckSize(u, num_dofs(), "Energy");
  return 0.5 * u.dot(stiffness_ * u);
}

void PlaneStressQ4::InternalForce(const Vec& u, Vec* force) const {
  CheckSize(u, num_dofs(), "InternalForce");
  force->noalias() = stiffness_ * u;
}

void PlaneStressQ4::Stiffness(const Vec& u, SpMat* stiffness) const {
  CheckSize(u, num_dofs(), "Stiffness");
  *stiffness = stiffness_;
}

std::vector<std::pair<int, int>> PlaneStressQ4::StiffnessEntries() const {
  std::vector<std::pair<int, int>> entries;
  entries.reserve(stiffness_.nonZeros());
  for (int j = 0; j < stiffness_.outerSize(); ++j) {
    for (SpMat::InnerIterator it(stiffness_, j); it; ++it) {
      entries.emplace_back(static_cast<int>(it.row()), j);
    }
  }
  return entries;
}

void PlaneStressQ4::AddStiffness(const Vec& u, double scale, const int* slots,
                                 double* values) const {
  CheckSize(u, num_dofs(), "AddStiffness");
  const double* k = stiffness_.valuePtr();
  for (Eigen::Index i = 0; i < stiffness_.nonZeros(); ++i) values[slots[i]] += scale * k[i];
}

// A uniform traction t on a straight edge, interpolated by the linear edge shape functions:
// the consistent nodal force of each end is integral N_a t thickness ds = t thickness len / 2.
void PlaneStressQ4::AddEdgeTraction(int node_a, int node_b, const Point& traction,
                                    Vec* load) const {
  const int nodes = num_nodes();
  if (node_a < 0 || node_a >= nodes || node_b < 0 || node_b >= nodes) {
    throw std::invalid_argument("PlaneStressQ4::AddEdgeTraction: unknown node (" +
                                std::to_string(node_a) + ", " + std::to_string(node_b) + ")");
  }
  if (node_a == node_b) {
    throw std::invalid_argument("PlaneStressQ4::AddEdgeTraction: the edge joins node " +
                                std::to_string(node_a) + " to itself");
  }
  if (traction.size() != 2) {
    throw std::invalid_argument("PlaneStressQ4::AddEdgeTraction: traction has " +
                                std::to_string(traction.size()) + " components, expected 2");
  }
  const double length = (coordinates_.row(node_b) - coordinates_.row(node_a)).norm();
  const Point nodal = (0.5 * material_.thickness * length) * traction;
  AddNodalForce(dofs_, node_a, nodal, load);
  AddNodalForce(dofs_, node_b, nodal, load);
}

void AddNodalForce(const DofMap& dofs, int node, const Point& force, Vec* load) {
  if (node < 0 || node >= dofs.num_nodes()) {
    throw std::invalid_argument("AddNodalForce: unknown node " + std::to_string(node));
  }
  if (force.size() != dofs.dim()) {
    throw std::invalid_argument("AddNodalForce: force has " + std::to_string(force.size()) +
                                " components, expected " + std::to_string(dofs.dim()));
  }
  if (load->size() != dofs.num_dofs()) {
    throw std::invalid_argument("AddNodalForce: load has size " + std::to_string(load->size()) +
                                ", expected " + std::to_string(dofs.num_dofs()));
  }
  // A component on a support is carried by the support reaction, not by u.
  for (int c = 0; c < dofs.dim(); ++c) {
    const int dof = dofs.dof(node, c);
    if (dof >= 0) (*load)[dof] += force[c];
  }
}

}  // namespace cb

namespace cb {

std::shared_ptr<const ElasticBody> PlaneStressQ4::Restricted(
    const std::vector<int>& elements) const {
  return std::make_shared<PlaneStressQ4>(coordinates_,
                                         SelectElements(elements_, elements, "PlaneStressQ4"),
                                         material_, dofs_.FixedComponents());
}

std::vector<std::vector<int>> PlaneStressQ4::Cells() const {
  std::vector<std::vector<int>> cells;
  cells.reserve(elements_.size());
  for (const Element& e : elements_) cells.emplace_back(e.begin(), e.end());
  return cells;
}

std::vector<CellField> PlaneStressQ4::CellFields(const Vec& u) const {
  // ElasticityMatrix carries the thickness; the stress is D eps without it.
  const Eigen::Matrix3d d = ElasticityMatrix(material_) / material_.thickness;
  CellField sxx{"stress_xx", {}}, syy{"stress_yy", {}}, sxy{"stress_xy", {}};
  CellField mises{"von_mises_stress", {}};
  CellField tensor{"stress", {}, 9};  // the plane stress state as a 3-D tensor (z row 0)
  for (const Element& e : elements_) {
    Eigen::Matrix<double, 4, 2> xy;
    Eigen::Matrix<double, 8, 1> ue;
    for (int a = 0; a < 4; ++a) {
      xy.row(a) = coordinates_.row(e[a]);
      const Point moved = Position(e[a], u);
      ue(2 * a) = moved[0] - xy(a, 0);
      ue(2 * a + 1) = moved[1] - xy(a, 1);
    }
    Mat38 b;
    double det = 0.0;
    StrainDisplacement(xy, 0.0, 0.0, &b, &det);  // checked at construction
    const Eigen::Vector3d sigma = d * (b * ue);
    sxx.values.push_back(sigma[0]);
    syy.values.push_back(sigma[1]);
    sxy.values.push_back(sigma[2]);
    tensor.values.insert(tensor.values.end(),
                         {sigma[0], sigma[2], 0.0, sigma[2], sigma[1], 0.0, 0.0, 0.0, 0.0});
    mises.values.push_back(std::sqrt(sigma[0] * sigma[0] - sigma[0] * sigma[1] +
                                     sigma[1] * sigma[1] + 3.0 * sigma[2] * sigma[2]));
  }
  return {sxx, syy, sxy, mises, tensor};
}

}  // namespace cb
