// The objective and constraint functions the NLopt formulations hand to NLopt, kept free of
// NLopt itself so that the tests can check every derivative against finite differences and so
// that the functions are the same whether or not NLopt was found.
#pragma once

#include <memory>
#include <vector>

#include "formulations/implicit_fb/implicit_fb_system.h"
#include "step/step_problem.h"

namespace cb {

// nlopt-merit: m(x) = 1/2 ||F(x)||^2 of the implicit smoothed-FB system (29)-(33) in its scaled
// unknowns x = (du, g/L, r/R, dlambda, rho) (ImplicitFbSystem), gradient J(x)^T F(x) from the
// system's sparse Jacobian. NLopt sees it in the variables y = sqrt(s) x as
//   M(y) = s m(y / sqrt(s)),   grad_y M = sqrt(s) J^T F,
// with s = merit_scale. A quasi-Newton method's iterates are the same in x and in y (its first
// step, -grad, included: y1 = y0 - sqrt(s) grad m is x1 = x0 - grad m), but NLopt's absolute
// gradient test (see NloptMeritOptions::merit_scale) then applies to sqrt(s) grad m.
class NloptMeritObjective {
 public:
  NloptMeritObjective(const StepProblem& step, EtaEquation eta, double scale);
  int size() const { return system_.size(); }
  const StepEquationLayout& layout() const { return system_.layout(); }
  // M(y), and grad_y M into *gradient when it is not null. +infinity when F is not finite at
  // y / sqrt(s) (NLopt's line searches then shorten the step).
  double Evaluate(const Vec& y, Vec* gradient);
  Vec ToNlopt(const Vec& x) const { return root_scale_ * x; }
  Vec FromNlopt(const Vec& y) const { return y / root_scale_; }
  // F at the last Evaluate, and m = 1/2 ||F||^2 there.
  const Vec& residual() const { return residual_; }
  double merit() const { return 0.5 * residual_.squaredNorm(); }
  double scale() const { return scale_; }

 private:
  ImplicitFbSystem system_;
  double scale_;
  double root_scale_;
  Vec x_, residual_;
  SpMat jacobian_;
};

// nlopt-energy: the fixed-load step as  min pi(u) - lambda f^T u  s.t.  phi(u) <= 0, with
// u = u^k + L y in the dimensionless unknowns y = du / L, objective divided by R L and
// constraints by L:
//   E(y) = (pi(u) - lambda f^T u) / (R L),   grad E = (grad pi(u) - lambda f) / R,
//   c_p(y) = phi_p(u) / L <= 0,               dc_p/dy = row p of grad phi(u).
// Both are O(1) with the problem's contact scales, so the NLopt tolerances mean the same thing
// on every problem.
class NloptEnergyProblem {
 public:
  // Throws std::invalid_argument for a step that IsEnergyStep refuses (common/energy_step.h).
  explicit NloptEnergyProblem(const StepProblem& step);
  int size() const { return step_.num_dofs(); }
  int num_constraints() const { return step_.num_pairs(); }
  double lambda() const { return lambda_; }
  double Objective(const Vec& y, Vec* gradient) const;
  // c into `values` (size nc); when `dense_gradient` is not null, the nc x d row-major array
  // NLopt's vector-valued constraints want (dense_gradient[p * d + j] = dc_p / dy_j), all of it
  // written (zeros included).
  void Constraints(const Vec& y, double* values, double* dense_gradient) const;
  // The answer at y: du = L y, g = -phi(u), and the reactions NLopt does not return, recovered
  // from (29) restricted to the pairs with g_p / L <= active_tol:
  //   min || grad pi(u) - lambda f - G_A^T r_A ||_2  subject to r_A <= 0,
  // solved by sparse QR on the active set, dropping the most positive reaction and solving again
  // until every reaction is <= 0 (a simple active-set loop, enough for the well-separated
  // contacts of these problems; the verdict judges the result). Pairs outside A get r = 0.
  StepPoint Recover(const Vec& y, double active_tol, int* active_pairs) const;

 private:
  const StepProblem& step_;
  double lambda_;
};

// nlopt-mpcc: the step NLP in the unknowns z = (du, g^ = g/L, r^ = r/R, dlambda), n = d + 2 nc + 1:
//   min  w sum_p (-g^_p r^_p)                          (exact penalty of (11); >= 0 on the bounds)
//   s.t. (29) / R, (30) / L and the step constraint c = 0 (StepConstraintValue), d + nc + 1 rows,
//        g^ >= 0, r^ <= 0.
// The equality rows and their Jacobian are those of ImplicitFbSystem ((29), (30), (33) rows,
// evaluated with rho = 0 and its rho column dropped), so they are not derived a second time.
class NloptMpccProblem {
 public:
  NloptMpccProblem(const StepProblem& step, double weight);
  int size() const { return layout_.size() - 1; }  // the implicit layout without rho
  int num_equalities() const { return layout_.d + layout_.nc + 1; }
  const StepEquationLayout& layout() const { return layout_; }
  double Objective(const Vec& z, Vec* gradient) const;
  // The equality rows into `values`; when `dense_gradient` is not null, the m x n row-major
  // Jacobian (m = num_equalities(), n = size()), every entry written.
  void Equalities(const Vec& z, double* values, double* dense_gradient);
  // g^ >= 0, r^ <= 0, the rest free.
  void Bounds(std::vector<double>* lower, std::vector<double>* upper) const;
  StepPoint Point(const Vec& z) const;

 private:
  const StepProblem& step_;
  double weight_;
  StepEquationLayout layout_;
  ImplicitFbSystem system_;
  Vec x_, residual_;
  SpMat jacobian_;
};

}  // namespace cb
