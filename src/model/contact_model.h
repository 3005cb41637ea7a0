// The abstract contact model of docs/method.md section 1: everything a formulation may ask of a
// discretised body and its contact candidates. Evaluation only, no state about steps or solvers.
#pragma once

#include <utility>
#include <vector>

#include "core/types.h"

namespace cb {

class ContactModel {
 public:
  virtual ~ContactModel() = default;

  // d, the number of displacement unknowns.
  virtual int num_dofs() const = 0;
  // nc, the number of contact candidates (pairs).
  virtual int num_pairs() const = 0;

  // True when grad pi is the gradient of an energy (Energy() is then defined and Stiffness()
  // symmetric). A generic complementarity model may have a non-symmetric "internal force".
  virtual bool has_energy() const { return true; }
  // True for small deformation: quadratic energy and affine gaps (stiffness and gap Jacobian
  // do not depend on u, and GapCurvature is zero).
  virtual bool is_linear() const { return false; }
  // True when hess pi does not depend on u (a small-deformation body, whatever its obstacles):
  // the reduced Newton of formulations/common/reduced_step_system.h eliminates its interior once.
  virtual bool has_constant_stiffness() const { return is_linear(); }

  // pi(u), the strain energy.
  virtual double Energy(const Vec& u) const = 0;
  // grad pi(u), the internal force (size d).
  virtual void InternalForce(const Vec& u, Vec* force) const = 0;
  // hess pi(u), the tangent stiffness (d x d). Its sparsity pattern does not depend on u.
  virtual void Stiffness(const Vec& u, SpMat* stiffness) const = 0;
  // Per dof, the sum of the magnitudes of the terms InternalForce adds up in that row: the
  // rounding floor of grad pi(u), and so of (29) (StepEquationSystem::ResidualFloor). The
  // default, |K(u)| |u|, is exact for a linear model (grad pi = K u) and an upper bound
  // otherwise; element-by-element models sum their elements' |f_e|.
  virtual void InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const {
    SpMat stiffness;
    Stiffness(u, &stiffness);
    *magnitudes = stiffness.cwiseAbs() * u.cwiseAbs();
  }

  // The stiffness as a stream of contributions, to assemble it straight into a larger matrix
  // (the Jacobian of a step) without an intermediate matrix: StiffnessEntries() lists the
  // (row, col) of every contribution in the order AddStiffness adds them, and AddStiffness adds
  // scale * (k-th contribution at u) to values[slots[k]]. The defaults go through Stiffness();
  // element-by-element models override both.
  virtual std::vector<std::pair<int, int>> StiffnessEntries() const {
    SpMat k;
    Stiffness(Vec::Zero(num_dofs()), &k);
    std::vector<std::pair<int, int>> entries;
    for (int j = 0; j < k.outerSize(); ++j) {
      for (SpMat::InnerIterator it(k, j); it; ++it) {
        entries.emplace_back(static_cast<int>(it.row()), j);
      }
    }
    return entries;
  }
  virtual void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const {
    SpMat k;
    Stiffness(u, &k);
    for (Eigen::Index i = 0; i < k.nonZeros(); ++i) values[slots[i]] += scale * k.valuePtr()[i];
  }

  // grad pi(u) into *force and, as AddStiffness, scale * hess pi(u) into values[slots[k]]: the
  // elastic part of a residual and of a Jacobian at the same u, each element visited once. Equal
  // bit for bit to InternalForce followed by AddStiffness (the default).
  virtual void InternalForceAndStiffness(const Vec& u, Vec* force, double scale, const int* slots,
                                         double* values) const {
    InternalForce(u, force);
    AddStiffness(u, scale, slots, values);
  }

  // phi(u): phi_p = varphi_p(x_p(u)), positive when the node is inside obstacle p (size nc).
  // The gap is g = -phi.
  virtual void Gaps(const Vec& u, Vec* phi) const = 0;
  // grad phi(u) (nc x d): row p is the obstacle's normal on pair p's node dofs.
  virtual void GapJacobian(const Vec& u, SpMat* jacobian) const = 0;
  // grad phi(u)^T r (size d), the generalised reaction of (9). The default forms the gap
  // Jacobian; models override it to avoid assembling a matrix only to multiply it.
  virtual void GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const {
    SpMat jacobian;
    GapJacobian(u, &jacobian);
    *reaction = jacobian.transpose() * r;
  }
  // sum_p r_p hess phi_p(u) (d x d), the curvature term of curved obstacles. Its pattern
  // depends on neither u nor r (pairs on flat obstacles contribute nothing).
  virtual void GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const = 0;
  // The contact part of a residual, phi(u) and grad phi(u)^T r, and of a Jacobian, grad phi(u)
  // and sum_p r_p hess phi_p(u), each pair in one pass: a Newton iteration needs both members
  // of each couple at the same u. The defaults call the single functions; models whose pairs
  // share work between them override.
  virtual void GapsAndReaction(const Vec& u, const Vec& r, Vec* phi, Vec* reaction) const {
    Gaps(u, phi);
    GeneralisedReaction(u, r, reaction);
  }
  virtual void GapDerivatives(const Vec& u, const Vec& r, SpMat* jacobian, SpMat* curvature) const {
    GapJacobian(u, jacobian);
    GapCurvature(u, r, curvature);
  }

  // GapsAndReaction(u, r) and GapDerivatives(u, curvature_r) at the same u in one pass, each
  // pair's obstacle evaluated once: the contact part of a residual and of a Jacobian together.
  // The two weights differ when the residual and the Jacobian use the reactions in different
  // units. Equal bit for bit to the two calls (the default).
  virtual void GapsReactionAndDerivatives(const Vec& u, const Vec& r, const Vec& curvature_r,
                                          Vec* phi, Vec* reaction, SpMat* jacobian,
                                          SpMat* curvature) const {
    GapsAndReaction(u, r, phi, reaction);
    GapDerivatives(u, curvature_r, jacobian, curvature);
  }

  // f: the external load is lambda f (size d).
  virtual const Vec& load_pattern() const = 0;
};

}  // namespace cb
