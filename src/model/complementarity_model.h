// A generic complementarity problem behind the ContactModel interface, so that every
// formulation can be run on textbook LCPs and NCPs with known answers.
//
//   LCP: w = M z + q,  z >= 0, w >= 0, z^T w = 0     (M dense or sparse, n x n)
//   NCP: w = F(z),     z >= 0, w >= 0, z^T w = 0     (F and its Jacobian by callbacks)
//
// The map onto docs/method.md section 1: d = nc = n, one pair per unknown with
//   phi_p(u) = -u_p       (so the gap g = -phi(u) = z, and grad phi = -I),
//   grad pi(u) = F(u)     (InternalForce; = M u + q for an LCP),
//   hess pi(u) = dF(u)    (Stiffness; = M),
//   f = 0, sum_p r_p hess phi_p = 0.
// With lambda = 0 the step equations (29)-(30) read F(z) + r = 0, i.e. r = -w <= 0, and (11)
// is exactly the complementarity problem; the verdict is then its natural residual:
// eq_res = ||F(z) + r||_inf, comp_res = ||min(z / L, w / R)||_inf (L, R: DataScales).
// There is an energy only when M is symmetric (pi = 1/2 z^T M z + q^T z); an NCP given by
// callbacks has none.
#pragma once

#include <functional>
#include <string>

#include "model/contact_model.h"

namespace cb {

class ComplementarityModel final : public ContactModel {
 public:
  using Function = std::function<void(const Vec& z, Vec* value)>;
  // The n x n Jacobian dF(z), dense: the NCPs this is meant for are small (the model stores it
  // with a full, fixed sparsity pattern, the one exception to "sparse throughout").
  using DenseJacobian = std::function<void(const Vec& z, Mat* jacobian)>;

  // Throw std::invalid_argument naming the field: M not square or empty, q of another size,
  // non-finite entries, a null callback, n < 1.
  static ComplementarityModel Lcp(const SpMat& m, const Vec& q);
  static ComplementarityModel Lcp(const Mat& m, const Vec& q);
  static ComplementarityModel Ncp(int n, Function f, DenseJacobian jacobian);

  int num_dofs() const override { return n_; }
  int num_pairs() const override { return n_; }
  // True for an LCP whose M is symmetric (to a relative 1e-14).
  bool has_energy() const override { return symmetric_; }
  bool is_linear() const override { return linear_; }

  // 1/2 z^T M z + q^T z; throws std::invalid_argument when has_energy() is false.
  double Energy(const Vec& u) const override;
  void InternalForce(const Vec& u, Vec* force) const override;
  void Stiffness(const Vec& u, SpMat* stiffness) const override;
  void Gaps(const Vec& u, Vec* phi) const override;
  void GapJacobian(const Vec& u, SpMat* jacobian) const override;
  void GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const override;
  void GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const override;
  const Vec& load_pattern() const override { return load_; }

  // The sizes of z and of w = F(z) the data imply, the default length and force scales L, R of
  // a complementarity problem (docs/method.md section 2): R = ||F(0)||_inf (||q||_inf for an
  // LCP), a typical w, and L = R / ||dF(0)||_inf (row-sum norm; ||M||_inf), the z that the
  // Jacobian maps onto such a w. So g/L and r/R are O(1) for every formulation whatever units
  // the data come in. Each is 1 when the data give no size (F(0) = 0 or dF(0) = 0).
  void DataScales(double* length, double* force) const;

  // The complementarity residual of a candidate z: ||min(z, F(z))||_inf.
  double NaturalResidual(const Vec& z) const;

 private:
  ComplementarityModel() = default;
  void CheckSize(const Vec& u, const char* what) const;

  int n_ = 0;
  bool linear_ = false;
  bool symmetric_ = false;
  SpMat m_;  // LCP
  Vec q_;    // LCP
  Function f_;
  DenseJacobian jacobian_;
  Vec load_;
};

}  // namespace cb
