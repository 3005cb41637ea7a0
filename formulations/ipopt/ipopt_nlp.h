// The NLPs that the Ipopt formulations hand to Ipopt, written without Ipopt's types so that
// the tests can check their derivatives without Ipopt's headers (docs/architecture.md, house rule
// 4).
//
// Both NLPs work in scaled unknowns (docs/method.md sections 2 and 9): a
// displacement increment is measured in the contact length scale L (x_u = du / L), a gap in L
// (g^ = g / L) and a reaction in the force scale R (r^ = r / R), so that every unknown is O(1)
// at the solution and the rows below are dimensionless. Ipopt's own gradient-based scaling is
// switched off (nlp_scaling_method = none): this is the only scaling.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"
#include "step/step_problem.h"

namespace cb {

// min f(x) s.t. c_lower <= c(x) <= c_upper, x_lower <= x <= x_upper, with the constraint
// Jacobian and the lower triangle of the Lagrangian Hessian in triplet form (Ipopt's TNLP
// shape: duplicate entries are summed). The Lagrangian is Ipopt's:
//   sigma f(x) + sum_i y_i c_i(x).
// Evaluations return false on non-finite values or on a model whose sparsity pattern changed.
class IpoptNlp {
 public:
  virtual ~IpoptNlp() = default;

  int num_variables() const { return static_cast<int>(x_lower_.size()); }
  int num_constraints() const { return static_cast<int>(c_lower_.size()); }
  const Vec& x_lower() const { return x_lower_; }
  const Vec& x_upper() const { return x_upper_; }
  const Vec& c_lower() const { return c_lower_; }
  const Vec& c_upper() const { return c_upper_; }
  const std::vector<int>& jacobian_rows() const { return jacobian_rows_; }
  const std::vector<int>& jacobian_cols() const { return jacobian_cols_; }
  const std::vector<int>& hessian_rows() const { return hessian_rows_; }
  const std::vector<int>& hessian_cols() const { return hessian_cols_; }

  virtual bool Objective(const Vec& x, double* f) = 0;
  virtual bool Gradient(const Vec& x, Vec* gradient) = 0;
  virtual bool Constraints(const Vec& x, Vec* c) = 0;
  virtual bool JacobianValues(const Vec& x, Vec* values) = 0;
  virtual bool HessianValues(const Vec& x, double sigma, const Vec& y, Vec* values) = 0;

  // Infinity as Ipopt understands it (below nlp_upper_bound_inf = 1e19 counts as finite).
  static constexpr double kInfinity = 2e19;

 protected:
  Vec x_lower_, x_upper_, c_lower_, c_upper_;
  std::vector<int> jacobian_rows_, jacobian_cols_, hessian_rows_, hessian_cols_;
};

// `ipopt-energy`: a fixed-load step as energy minimisation (small or large deformation alike),
//   min  (pi(u) - lambda f^T u) / (R L)   s.t.  phi_p(u) / L <= 0,   u = u^k + L x,
// lambda the step's target. Its KKT conditions are (9)-(11) with r = -R y (y >= 0 Ipopt's
// multiplier of the upper bound c <= 0): grad pi - lambda f + grad phi^T (R y) = 0.
// Throws std::invalid_argument for a step that IsEnergyStep refuses (common/energy_step.h).
class EnergyNlp final : public IpoptNlp {
 public:
  explicit EnergyNlp(const StepProblem& step);

  bool Objective(const Vec& x, double* f) override;
  bool Gradient(const Vec& x, Vec* gradient) override;
  bool Constraints(const Vec& x, Vec* c) override;
  bool JacobianValues(const Vec& x, Vec* values) override;
  // sigma (L / R) hess pi + L sum_p y_p hess phi_p (Stiffness and GapCurvature).
  bool HessianValues(const Vec& x, double sigma, const Vec& y, Vec* values) override;

 private:
  const Vec& U(const Vec& x);
  const StepProblem& step_;
  double length_, force_, lambda_;
  long nnz_stiffness_ = 0, nnz_curvature_ = 0, nnz_gap_ = 0;
  Vec u_, work_;
  SpMat stiffness_, curvature_, gap_jacobian_;
};

enum class MpccReformulation { kScholtes, kPenalty };
const char* ToString(MpccReformulation reformulation);

// `ipopt-mpcc`: one step (any StepConstraint kind) as an NLP in x = (du / L, g / L, r / R,
// dlambda), n = d + 2 nc + 1:
//   rows  F1 = (grad pi(u) - (lambda^k + dlambda) f) / R - grad phi(u)^T r^ = 0    (29) / R
//         F2 = g^ + phi(u) / L = 0                                                (30) / L
//         c  = StepConstraintValue(...) = 0       (33) / theta^2 - 1, fixed load, displacement
//         S_p = -g^_p r^_p <= t                   Scholtes relaxation of (11) (kScholtes only)
//   bounds g^ >= 0, r^ <= 0                       (11), sign part
//   objective 0 (kScholtes) or penalty_weight sum_p (-g^_p r^_p) (kPenalty, exact penalty)
// A kink step (53) g^_p - r^_p = 0 together with the bounds says g^_p = r^_p = 0; an interior
// point method cannot reach that equality from inside the bounds (the barrier subproblem has no
// interior), so for the kink pair both variables are fixed at 0 by their bounds and the row is
// left out (its value is then identically 0).
//
// The Hessian of the (29) rows needs third derivatives of pi and phi, which ContactModel does
// not offer: sum_i y_i hess F1_i has the block (L^2 / R) d/du [(hess pi - sum_p r_p hess phi_p)
// y]. It is formed by central differences of Stiffness and GapCurvature along a colouring of
// their joint pattern (columns sharing no row are perturbed together), then symmetrised; zero for
// small-deformation models (is_linear()). Every other term is exact. At a solution the (29)
// multipliers vanish in the strictly complementary case (the objective's gradient is taken by the
// bound multipliers), so this term does not limit the local convergence rate either.
class MpccNlp final : public IpoptNlp {
 public:
  MpccNlp(const StepProblem& step, MpccReformulation reformulation, double penalty_weight);

  // Layout of x and of the rows.
  int ix_u() const { return 0; }
  int ix_g() const { return d_; }
  int ix_r() const { return d_ + nc_; }
  int ix_dlambda() const { return d_ + 2 * nc_; }
  int row_step() const { return has_step_row_ ? d_ + nc_ : -1; }
  int row_scholtes() const { return d_ + nc_ + (has_step_row_ ? 1 : 0); }
  MpccReformulation reformulation() const { return reformulation_; }
  // The relaxation t of the Scholtes rows (their upper bound).
  void set_relaxation(double t);
  double relaxation() const { return relaxation_; }
  // The weight of the penalty objective (kPenalty).
  void set_penalty_weight(double weight) { penalty_weight_ = weight; }

  bool Objective(const Vec& x, double* f) override;
  bool Gradient(const Vec& x, Vec* gradient) override;
  bool Constraints(const Vec& x, Vec* c) override;
  bool JacobianValues(const Vec& x, Vec* values) override;
  bool HessianValues(const Vec& x, double sigma, const Vec& y, Vec* values) override;

 private:
  // The steps of the constructor: the joint pattern of stiffness and curvature with its slots
  // and colouring, the bounds, and the Jacobian's and the Hessian's structures.
  void BuildJointPattern();
  void SetBounds();
  void AppendJacobianStructure();
  void AppendHessianStructure();
  bool Evaluate(const Vec& x);  // u, stiffness, curvature (at r = R r^), gap Jacobian
  bool ThirdOrderTerm(const Vec& x, const Vec& y, Vec* joint_values);  // see the class comment

  const StepProblem& step_;
  MpccReformulation reformulation_;
  double penalty_weight_;
  double relaxation_ = 1.0;
  int d_, nc_;
  double length_, force_;
  bool has_step_row_ = true;
  bool curved_ = false;  // GapCurvature has entries
  bool linear_ = false;  // model->is_linear(): no third-order term
  std::vector<int> load_rows_;
  long nnz_stiffness_ = 0, nnz_curvature_ = 0, nnz_gap_ = 0;
  // Joint pattern P of stiffness and curvature (symmetric), its lower entries' Hessian slots,
  // the position of each entry's transpose, the slot of each curvature entry in P, and the
  // column colouring for the finite differences.
  SpMat joint_;
  std::vector<int> joint_transpose_;
  std::vector<int> joint_lower_slot_;  // -1 for upper entries
  std::vector<int> curvature_to_joint_;
  std::vector<int> colour_;
  int num_colours_ = 0;
  int first_cross_ = 0;  // first Hessian slot of the (r^_p, du) block
  Vec u_, work_, v_plus_, v_minus_;
  SpMat stiffness_, curvature_, gap_jacobian_, work_stiffness_, work_curvature_;
};

}  // namespace cb
