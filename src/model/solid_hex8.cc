#include "model/solid_hex8.h"

#include <Eigen/Geometry>  // cross product
#include <Eigen/LU>        // 3 x 3 determinant and inverse
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "model/plane_stress_q4.h"  // AddNodalForce

namespace cb {
namespace {

using Mat83 = Eigen::Matrix<double, 8, 3>;
using Mat24 = Eigen::Matrix<double, 24, 24>;

// Natural coordinates of the eight nodes (VTK / Gmsh order).
constexpr double kXiNode[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
constexpr double kEtaNode[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
constexpr double kZetaNode[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

[[noreturn]] void ThrowElement(std::size_t element, const std::string& reason) {
  throw std::invalid_argument("SolidHex8: element " + std::to_string(element) + " " + reason);
}

void CheckSize(const Vec& u, int num_dofs, const char* what) {
  if (u.size() != num_dofs) {
    throw std::invalid_argument(std::string("SolidHex8::") + what + ": u has size " +
                                std::to_string(u.size()) + ", expected " +
                                std::to_string(num_dofs));
  }
}

// Reference gradients dN_a/dX (row a) of the trilinear shape functions
// N_a = (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a) / 8 at a natural point, and det J there.
// False when det J <= 0 (a flat or inverted element).
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

// The 2 x 2 x 2 Gauss point gp (unit weights) in natural coordinates.
void GaussPoint(int gp, double* xi, double* eta, double* zeta) {
  const double g = 1.0 / std::sqrt(3.0);
  *xi = (gp & 1) ? g : -g;
  *eta = (gp & 2) ? g : -g;
  *zeta = (gp & 4) ? g : -g;
}

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

}  // namespace

SolidHex8::SolidHex8(Mat coordinates, std::vector<Element> elements, const SolidMaterial& material,
                     SolidKinematics kinematics, const std::vector<bool>& fixed)
    : coordinates_(std::move(coordinates)),
      elements_(std::move(elements)),
      material_(material),
      kinematics_(kinematics) {
  if (coordinates_.cols() != 3) {
    throw std::invalid_argument("SolidHex8: coordinates have " +
                                std::to_string(coordinates_.cols()) + " columns, expected 3");
  }
  for (Eigen::Index n = 0; n < coordinates_.rows(); ++n) {
    if (!coordinates_.row(n).allFinite()) {
      throw std::invalid_argument("SolidHex8: node " + std::to_string(n) +
                                  " has non-finite coordinates");
    }
  }
  if (!(material_.youngs_modulus > 0.0) || !std::isfinite(material_.youngs_modulus)) {
    throw std::invalid_argument("SolidHex8: Young's modulus must be positive, got " +
                                std::to_string(material_.youngs_modulus));
  }
  const double nu = material_.poisson_ratio;
  if (!(nu > -1.0 && nu < 0.5)) {
    throw std::invalid_argument("SolidHex8: Poisson's ratio must lie in (-1, 0.5), got " +
                                std::to_string(nu));
  }
  lame_lambda_ = material_.youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  shear_modulus_ = material_.youngs_modulus / (2.0 * (1.0 + nu));
  const int nodes = num_nodes();
  if (!fixed.empty() && fixed.size() != static_cast<std::size_t>(nodes) * 3) {
    throw std::invalid_argument("SolidHex8: `fixed` has " + std::to_string(fixed.size()) +
                                " entries, expected num_nodes * 3 = " + std::to_string(3 * nodes) +
                                " (or none)");
  }
  dofs_ = DofMap(nodes, 3, fixed);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Element& el = elements_[e];
    for (int a = 0; a < 8; ++a) {
      if (el[a] < 0 || el[a] >= nodes) {
        ThrowElement(e, "names an unknown node " + std::to_string(el[a]) + " (the mesh has " +
                            std::to_string(nodes) + " nodes)");
      }
      for (int b = 0; b < a; ++b) {
        if (el[a] == el[b]) ThrowElement(e, "repeats node " + std::to_string(el[a]));
      }
    }
    if (!HasPositiveJacobian(coordinates_, el)) {
      ThrowElement(e,
                   "has a non-positive Jacobian (flat, or nodes not in the order 0-1-2-3 "
                   "counter-clockwise below 4-5-6-7)");
    }
  }

  // Sparsity pattern in compressed column form: K(i, j) is structurally non-zero iff the nodes
  // of dofs i and j share an element. Node adjacency (self included) as sorted, unique CSR.
  std::vector<int> adj_start(nodes + 1, 0);
  for (const Element& el : elements_) {
    for (int a = 0; a < 8; ++a) adj_start[el[a] + 1] += 8;
  }
  for (int n = 0; n < nodes; ++n) adj_start[n + 1] += adj_start[n];
  std::vector<int> adj(adj_start[nodes]);
  {
    std::vector<int> cursor(adj_start.begin(), adj_start.end() - 1);
    for (const Element& el : elements_) {
      for (int a = 0; a < 8; ++a) {
        for (int b = 0; b < 8; ++b) adj[cursor[el[a]]++] = el[b];
      }
    }
  }
  const int d = dofs_.num_dofs();
  std::vector<int> outer(d + 1, 0);
  std::vector<int> inner;
  for (int n = 0; n < nodes; ++n) {
    const auto first = adj.begin() + adj_start[n];
    std::sort(first, adj.begin() + adj_start[n + 1]);
    const auto last = std::unique(first, adj.begin() + adj_start[n + 1]);
    for (int c = 0; c < 3; ++c) {
      const int j = dofs_.dof(n, c);
      if (j < 0) continue;
      for (auto m = first; m != last; ++m) {
        for (int c2 = 0; c2 < 3; ++c2) {
          const int i = dofs_.dof(*m, c2);
          if (i >= 0) inner.push_back(i);
        }
      }
      outer[j + 1] = static_cast<int>(inner.size());
    }
  }
  pattern_.resize(d, d);
  pattern_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), pattern_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), pattern_.innerIndexPtr());
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + inner.size(), 0.0);
  // Small deformation: K once, the tangent at u = 0.
  if (is_linear()) AssembleTangent(Vec::Zero(d), pattern_.valuePtr());
}

bool SolidHex8::HasPositiveJacobian(const Mat& coordinates, const Element& element) {
  Mat83 xyz;
  for (int a = 0; a < 8; ++a) xyz.row(a) = coordinates.row(element[a]);
  for (int gp = 0; gp < 8; ++gp) {
    double xi, eta, zeta, det;
    GaussPoint(gp, &xi, &eta, &zeta);
    Mat83 dn;
    if (!ShapeGradients(xyz, xi, eta, zeta, &dn, &det)) return false;
  }
  return true;
}

Eigen::Matrix<double, 8, 3> SolidHex8::ElementCoordinates(std::size_t element) const {
  Mat83 xyz;
  for (int a = 0; a < 8; ++a) xyz.row(a) = coordinates_.row(elements_[element][a]);
  return xyz;
}

Eigen::Matrix<double, 8, 3> SolidHex8::ElementDisplacements(std::size_t element,
                                                            const Vec& u) const {
  Mat83 ue;
  for (int a = 0; a < 8; ++a) {
    for (int c = 0; c < 3; ++c) {
      const int dof = dofs_.dof(elements_[element][a], c);
      ue(a, c) = dof >= 0 ? u[dof] : 0.0;
    }
  }
  return ue;
}

void SolidHex8::AssembleTangent(const Vec& u, double* values) const {
  const int* col_start = pattern_.outerIndexPtr();
  const int* rows = pattern_.innerIndexPtr();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Element& el = elements_[e];
    Mat83 xyz;
    int dof[24];
    for (int a = 0; a < 8; ++a) {
      xyz.row(a) = coordinates_.row(el[a]);
      for (int c = 0; c < 3; ++c) dof[3 * a + c] = dofs_.dof(el[a], c);
    }
    ElementResult result;
    if (!NeoHookeanElement(xyz, ElementDisplacements(e, u), lame_lambda_, shear_modulus_, true,
                           &result)) {
      result.tangent.setConstant(nan);  // an inverted element has no tangent
    }
    for (int b = 0; b < 24; ++b) {
      const int j = dof[b];
      if (j < 0) continue;
      const int* first = rows + col_start[j];
      const int* last = rows + col_start[j + 1];
      for (int a = 0; a < 24; ++a) {
        if (dof[a] < 0) continue;
        values[std::lower_bound(first, last, dof[a]) - rows] += result.tangent(a, b);
      }
    }
  }
}

double SolidHex8::Energy(const Vec& u) const {
  CheckSize(u, num_dofs(), "Energy");
  if (is_linear()) return 0.5 * u.dot(pattern_ * u);
  double energy = 0.0;
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Mat83 xyz = ElementCoordinates(e);
    ElementResult result;
    if (!NeoHookeanElement(xyz, ElementDisplacements(e, u), lame_lambda_, shear_modulus_, false,
                           &result)) {
      return std::numeric_limits<double>::infinity();
    }
    energy += result.energy;
  }
  return energy;
}

void SolidHex8::InternalForce(const Vec& u, Vec* force) const {
  CheckSize(u, num_dofs(), "InternalForce");
  if (is_linear()) {
    force->noalias() = pattern_ * u;
    return;
  }
  AssembleElementForces(u, force, false);
}

void SolidHex8::InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const {
  CheckSize(u, num_dofs(), "InternalForceMagnitudes");
  if (is_linear()) {
    *magnitudes = pattern_.cwiseAbs() * u.cwiseAbs();
    return;
  }
  AssembleElementForces(u, magnitudes, true);
}

void SolidHex8::AssembleElementForces(const Vec& u, Vec* force, bool magnitudes) const {
  force->setZero(num_dofs());
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Mat83 xyz = ElementCoordinates(e);
    ElementResult result;
    if (!NeoHookeanElement(xyz, ElementDisplacements(e, u), lame_lambda_, shear_modulus_, false,
                           &result)) {
      result.force.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    if (magnitudes) result.force = result.force.cwiseAbs();
    for (int a = 0; a < 8; ++a) {
      for (int c = 0; c < 3; ++c) {
        const int dof = dofs_.dof(elements_[e][a], c);
        if (dof >= 0) (*force)[dof] += result.force(a, c);
      }
    }
  }
}

void SolidHex8::Stiffness(const Vec& u, SpMat* stiffness) const {
  CheckSize(u, num_dofs(), "Stiffness");
  *stiffness = pattern_;
  if (is_linear()) return;
  std::fill(stiffness->valuePtr(), stiffness->valuePtr() + stiffness->nonZeros(), 0.0);
  AssembleTangent(u, stiffness->valuePtr());
}

std::vector<std::pair<int, int>> SolidHex8::StiffnessEntries() const {
  std::vector<std::pair<int, int>> entries;
  entries.reserve(pattern_.nonZeros());
  for (int j = 0; j < pattern_.outerSize(); ++j) {
    for (SpMat::InnerIterator it(pattern_, j); it; ++it) {
      entries.emplace_back(static_cast<int>(it.row()), j);
    }
  }
  return entries;
}

void SolidHex8::AddStiffness(const Vec& u, double scale, const int* slots, double* values) const {
  CheckSize(u, num_dofs(), "AddStiffness");
  const Eigen::Index nnz = pattern_.nonZeros();
  if (is_linear()) {
    const double* k = pattern_.valuePtr();
    for (Eigen::Index i = 0; i < nnz; ++i) values[slots[i]] += scale * k[i];
    return;
  }
  std::vector<double> tangent(static_cast<std::size_t>(nnz), 0.0);
  AssembleTangent(u, tangent.data());
  for (Eigen::Index i = 0; i < nnz; ++i) values[slots[i]] += scale * tangent[i];
}

std::shared_ptr<const ElasticBody> SolidHex8::Restricted(const std::vector<int>& elements) const {
  return std::make_shared<SolidHex8>(coordinates_, SelectElements(elements_, elements, "SolidHex8"),
                                     material_, kinematics_, dofs_.FixedComponents());
}

std::vector<std::vector<int>> SolidHex8::Cells() const {
  std::vector<std::vector<int>> cells;
  cells.reserve(elements_.size());
  for (const Element& e : elements_) cells.emplace_back(e.begin(), e.end());
  return cells;
}

std::vector<CellField> SolidHex8::CellFields(const Vec& u) const {
  CellField tensor{"stress", {}, 9};
  CellField mises{"von_mises_stress", {}};
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (const Eigen::Matrix3d& sigma : CauchyStress(u)) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) tensor.values.push_back(sigma(i, j));
    }
    const Eigen::Matrix3d dev = sigma - (sigma.trace() / 3.0) * identity;
    mises.values.push_back(std::sqrt(1.5 * dev.squaredNorm()));
  }
  return {mises, tensor};
}

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

std::vector<double> SolidHex8::VonMisesStress(const Vec& u) const {
  std::vector<double> out;
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (const Eigen::Matrix3d& sigma : CauchyStress(u)) {
    const Eigen::Matrix3d dev = sigma - (sigma.trace() / 3.0) * identity;
    out.push_back(std::sqrt(1.5 * dev.squaredNorm()));
  }
  return out;
}

std::vector<Eigen::Matrix3d> SolidHex8::CauchyStress(const Vec& u) const {
  CheckSize(u, num_dofs(), "CauchyStress");
  std::vector<Eigen::Matrix3d> out;
  out.reserve(elements_.size());
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Mat83 xyz = ElementCoordinates(e);
    Mat83 dn;
    double det0;
    ShapeGradients(xyz, 0.0, 0.0, 0.0, &dn, &det0);
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
