// A linear body given by its matrices, as the contact community's data sets (FCLIB's global
// problems) give it: no nodes and no obstacles, only
//
//   energy      pi(u) = 1/2 u^T K u                 (K n x n, symmetric)
//   gaps        g(u)  = N^T u + g0                  (N n x nc: column p is pair p's normal)
//   load        lambda f
//
// on the contract of docs/method.md section 1: phi(u) = -g(u), grad phi = -N^T, no curvature.
// With FCLIB's M v = H r + f, u = H^T v + w (docs/problem-files.md), K = M, N = H's normal
// columns, g0 = w's normal entries, and the suite's reaction is -r_N.
#pragma once

#include "model/contact_model.h"

namespace cb {

class LinearContactModel final : public ContactModel {
 public:
  // Throws std::invalid_argument naming the bad argument: K not square or empty, N or g0 or f of
  // another size, non-finite entries, or K not symmetric to 1e-14 relative to its largest entry
  // (grad pi = K u needs K = K^T).
  LinearContactModel(const SpMat& stiffness, const SpMat& normals, const Vec& initial_gaps,
                     const Vec& load_pattern);

  int num_dofs() const override { return static_cast<int>(stiffness_.rows()); }
  int num_pairs() const override { return static_cast<int>(normals_.cols()); }
  bool is_linear() const override { return true; }

  double Energy(const Vec& u) const override;
  void InternalForce(const Vec& u, Vec* force) const override;
  void Stiffness(const Vec& u, SpMat* stiffness) const override;
  void Gaps(const Vec& u, Vec* phi) const override;
  void GapJacobian(const Vec& u, SpMat* jacobian) const override;
  void GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const override;
  void GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const override;
  const Vec& load_pattern() const override { return load_; }

  const SpMat& normals() const { return normals_; }
  const Vec& initial_gaps() const { return initial_gaps_; }

 private:
  void CheckSize(const Vec& v, Eigen::Index n, const char* what) const;

  SpMat stiffness_;
  SpMat normals_;
  SpMat minus_normals_transposed_;  // grad phi = -N^T
  Vec initial_gaps_;
  Vec load_;
};

}  // namespace cb
