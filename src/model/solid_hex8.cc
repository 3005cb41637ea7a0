#include "model/solid_hex8.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "model/continuum_inputs.h"
#include "model/displacement_size.h"
#include "model/element_pattern.h"
#include "model/hex8_shape.h"
#include "model/neo_hookean_hex8.h"

namespace cb {
namespace {

using hex8::ElementResult;
using hex8::GaussPoint;
using hex8::Mat83;
using hex8::NeoHookeanElement;
using hex8::ShapeGradients;

[[noreturn]] void ThrowElement(std::size_t element, const std::string& reason) {
  throw std::invalid_argument("SolidHex8: element " + std::to_string(element) + " " + reason);
}

void CheckSize(const Vec& u, int num_dofs, const char* what) {
  CheckDisplacementSize(u, num_dofs, "SolidHex8", what);
}

// The inputs the constructor refuses: coordinates not n x 3 or not finite, a material out of
// range, a `fixed` of the wrong size.
void CheckInputs(const Mat& coordinates, const SolidMaterial& material,
                 const std::vector<bool>& fixed) {
  CheckNodeCoordinates("SolidHex8", coordinates, 3);
  CheckYoungsModulus("SolidHex8", material.youngs_modulus);
  CheckPoissonRatio("SolidHex8", material.poisson_ratio);
  CheckFixedSize("SolidHex8", fixed, static_cast<int>(coordinates.rows()), 3);
}

// Every element names eight distinct known nodes and has a positive Jacobian.
void CheckElements(const Mat& coordinates, const std::vector<SolidHex8::Element>& elements) {
  const auto nodes = static_cast<int>(coordinates.rows());
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const SolidHex8::Element& el = elements[e];
    for (int a = 0; a < 8; ++a) {
      if (el[a] < 0 || el[a] >= nodes) {
        ThrowElement(e, "names an unknown node " + std::to_string(el[a]) + " (the mesh has " +
                            std::to_string(nodes) + " nodes)");
      }
      for (int b = 0; b < a; ++b) {
        if (el[a] == el[b]) ThrowElement(e, "repeats node " + std::to_string(el[a]));
      }
    }
    if (!SolidHex8::HasPositiveJacobian(coordinates, el)) {
      ThrowElement(e,
                   "has a non-positive Jacobian (flat, or nodes not in the order 0-1-2-3 "
                   "counter-clockwise below 4-5-6-7)");
    }
  }
}

}  // namespace

SolidHex8::SolidHex8(Mat coordinates, std::vector<Element> elements, const SolidMaterial& material,
                     SolidKinematics kinematics, const std::vector<bool>& fixed)
    : coordinates_(std::move(coordinates)),
      elements_(std::move(elements)),
      material_(material),
      kinematics_(kinematics) {
  CheckInputs(coordinates_, material_, fixed);
  const double nu = material_.poisson_ratio;
  lame_lambda_ = material_.youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  shear_modulus_ = material_.youngs_modulus / (2.0 * (1.0 + nu));
  dofs_ = DofMap(num_nodes(), 3, fixed);
  CheckElements(coordinates_, elements_);
  pattern_ = ElementStiffnessPattern(dofs_, elements_);
  // Small deformation: K once, the tangent at u = 0.
  if (is_linear()) AssembleTangent(Vec::Zero(dofs_.num_dofs()), pattern_.valuePtr());
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

}  // namespace cb
