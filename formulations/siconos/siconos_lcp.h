// The dense LCP that Siconos's LCP solvers are given for a step, written without Siconos's types
// so that the tests check the reduction in every build.
//
//   w^ = M^ z^ + q^,   z^ >= 0,   w^ >= 0,   z^T w^ = 0,   in the scales L, R of
//   docs/method.md section 2 (z^ = -r / R, w^ = g / L), so both are O(1) at the solution.
//
// Two kinds of step reduce to it, both at fixed load (lambda = lambda^k + dlambda known):
//
//  - an LCP as it is (a linear ComplementarityModel, model/complementarity_model.h): with
//    phi(u) = -u and grad pi(u) = M u + q the step equations (29)-(30) read w = M z + q with
//    z = u = g and r = -w, so z^ = z / L, w^ = w / R and
//        M^ = (L / R) M,   q^ = q / R;
//    here the roles are swapped (z^ is the gap, w^ the reaction) as the LCP has them.
//
//  - a linear (small-deformation) model with a nonsingular stiffness K (grad pi affine, phi
//    affine: ContactModel::is_linear), after eliminating the displacements from (29):
//        K du = b + G^T r,   b = lambda f - grad pi(u^k),   G = grad phi,
//    so du = K^-1 (b + G^T r), and (30) gives the gap g = -phi(u^k) - G du. With z = -r:
//        g = G K^-1 G^T z - (phi(u^k) + G K^-1 b),
//    that is (scaled)
//        M^ = (R / L) G K^-1 G^T,   q^ = -(phi(u^k) + G K^-1 b) / L.
//    M^ is symmetric positive semidefinite (definite when G has full row rank), the case in
//    which Lemke's method always ends at a solution. K must be nonsingular: a body held only by
//    its contacts (P1 `block`, no supports) has rigid-body modes and cannot be reduced so.
#pragma once

#include <memory>
#include <string>

#include "core/types.h"
#include "solvers/linear_solver.h"
#include "step/step_problem.h"

namespace cb {

class SteppedLcp {
 public:
  enum class Kind { kAsGiven, kEliminatedDisplacements };

  // Whether `step` reduces to a dense LCP of at most `max_size` unknowns (the reasons above; a
  // singular K is found by factorising it with `linear_solver`). Otherwise false with the
  // reason, naming `formulation`, in *why.
  static bool CanReduce(const std::string& formulation, const StepProblem& step, int max_size,
                        const std::string& linear_solver, std::string* why);

  // The LCP of `step`. Throws std::invalid_argument when the step does not reduce (CanReduce's
  // reasons, without its size limit), naming the reason. `kind` forces the elimination for a linear
  // ComplementarityModel (whose K = M must then be nonsingular; the tests compare both routes).
  SteppedLcp(const StepProblem& step, const std::string& linear_solver);
  SteppedLcp(const StepProblem& step, const std::string& linear_solver, Kind kind);

  Kind kind() const { return kind_; }
  int size() const { return static_cast<int>(q_.size()); }
  // Column-major n x n, the storage Siconos's dense NumericsMatrix takes.
  const Mat& m() const { return m_; }
  const Vec& q() const { return q_; }

  // z^ of a point of the step (a start: the increment and the reactions), clipped at 0.
  Vec ZFromPoint(const Vec& du, const Vec& r) const;
  // The step's point (physical units) from z^: du, g from the model at u^k + du, r, dlambda.
  StepPoint PointFromZ(const Vec& z) const;

 private:
  // CanReduce without the factorisation of K (the constructor factorises it once, to use it).
  static bool CheckStep(const std::string& formulation, const StepProblem& step, int max_size,
                        std::string* why);
  void BuildAsGiven();
  void BuildEliminated(const std::string& linear_solver);

  const StepProblem& step_;
  Kind kind_;
  Mat m_;
  Vec q_;
  // Elimination only: K^-1 b and K^-1 G^T (d x nc), to recover du from z.
  Vec k_inv_b_;
  Mat k_inv_gt_;
};

}  // namespace cb
