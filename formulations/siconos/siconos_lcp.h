// The dense LCP that Siconos's LCP solvers are given for a step, written without Siconos's types
// so that the tests check the reduction in every build.
//
//   w^ = M^ z^ + q^,   z^ >= 0,   w^ >= 0,   z^T w^ = 0,
//
// in the scales L, R of docs/method.md section 2, so that both are O(1) at the solution. Three
// kinds of fixed-load step (lambda = lambda^k + dlambda known) reduce to it:
//
//  - kAsGiven: an LCP as it is (a linear ComplementarityModel, model/complementarity_model.h).
//    With phi(u) = -u and grad pi(u) = M u + q, (29)-(30) read w = M z + q with z = u = g and
//    r = -w, so z^ = z / L, w^ = w / R and
//        M^ = (L / R) M,   q^ = q / R.
//
//  - kEliminatedDisplacements: a linear (small-deformation) model, ContactModel::is_linear,
//    with a nonsingular stiffness K. (29) gives K du = b + G^T r with b = lambda f - grad pi(u^k)
//    and G = grad phi, so du = K^-1 (b + G^T r), and (30) the gap g = -phi(u^k) - G du. With
//    z^ = -r / R and w^ = g / L:
//        M^ = (R / L) G K^-1 G^T,   q^ = -(phi(u^k) + G K^-1 b) / L.
//    M^ is symmetric positive semidefinite, the case in which Lemke's method ends at a solution.
//    K is factorised once (sparse Cholesky: CHOLMOD's supernodal one where SuiteSparse was
//    built, so the nc right-hand sides G^T are solved in blocks with dense kernels); nothing of
//    size d x nc is kept.
//
//  - kEliminatedWithRigidModes: the same with a singular K, a body held only by its contacts
//    (P1 `block`: no supports). Its rigid-body modes N (K N = 0) leave the gap undetermined
//    along G N and ask N^T (b + G^T r) = 0 of the reactions. With K_c = K + c G^T G, nonsingular
//    when the contacts hold the body (c > 0 below), (29) reads
//        K_c du = b - c G^T phi(u^k) + G^T (r - c g),
//    and with A = G K_c^-1 G^T (symmetric) and h = -phi(u^k) - G K_c^-1 (b - c G^T phi(u^k)),
//    (30) becomes (I - c A) g = h - A r. The eigenvectors V1 of c A with eigenvalue 1 span the
//    rigid gaps G N; on the others, V2 with eigenvalues c s2 < 1, g is a function of r. So, with
//    free amplitudes a of the rigid gaps,
//        g = M z + q + V1 a,   V1^T z = e,   z = -r,
//        M = V2 diag(s2 / (1 - c s2)) V2^T,  q = V2 diag(1 / (1 - c s2)) V2^T h,
//        e = -diag(1 / s1) V1^T h,
//    a mixed LCP. Splitting a = a+ - a- (both >= 0) and the equality into two inequalities gives
//    the LCP of size nc + 2 m in (z^, a+^, a-^) (a^ = a / L):
//        [ M^     V1  -V1 ]        [ q^     ]
//        [ -V1^T  0    0  ]  and   [  e / R ]
//        [  V1^T  0    0  ]        [ -e / R ],   M^ = (R / L) M,  q^ = q / L,
//    positive semidefinite (the coupling is skew), so Lemke's method still ends at a solution;
//    its a+ and a- are not unique, which the Newton solvers may not like (and c A's eigenvalue
//    1 is found as > 1/2: c is 1e-3 times the smallest diagonal entry of K on a contact dof, so
//    the elastic eigenvalues c s2 = c lambda_C / (1 + c lambda_C) of a contact compliance
//    lambda_C stay far below 1/2).
//    The eigenvalue 1 is multiple (m = 3 for P1), so any orthonormal basis of the rigid gaps is
//    an eigenbasis, and the eigensolver's is chosen by the rounding of A (the BLAS threads of
//    the sparse solves move it), while Lemke's pivots depend on the basis: V1 is taken
//    canonical instead (CanonicalRigidBasis: fixed vectors projected onto the rigid space,
//    orthonormalised in order), which depends on the space only, and e = -S1^-1 V1^T h with
//    S1 = V1^T A V1 (~ I / c), the form that holds for any basis of the space.
//    As two rows, the equality is degenerate: with Lemke's covering vector d = 1 the rows of
//    a+ and a- add up to w+ + w- = 2 z0, so both are 0 at every solution, z0's row ties exactly
//    with one of them at Lemke's last pivot (a tie that the last bit decides: if the w row
//    leaves, z0 stays basic and the path can end on a ray), and a+, a- solve for a = a+ - a-
//    only (the Newton solvers' singular matrices). Both rows are therefore relaxed by
//        delta = 1e-12 max(1, |e / R|_inf):   e / R + delta  and  -e / R + delta,
//    so that |V1^T z^ - e / R| <= delta: w+ + w- = 2 delta > 0 at every solution, z0 leaves
//    alone, and at most one of a+, a- is positive (a is unique). The answer balances the load
//    along the rigid modes to delta R in each component of V1^T r, 1e-12 of the reactions'
//    scale; the verdict judges the recovered point on the step's own rows (29)-(30), not on
//    this LCP, so a relaxation that mattered would show there (at 1e-8).
#pragma once

#include <memory>
#include <string>

#include "core/types.h"
#include "step/step_problem.h"

namespace cb {

class SteppedLcp {
 public:
  enum class Kind { kAsGiven, kEliminatedDisplacements, kEliminatedWithRigidModes };

  // Whether `step` reduces to a dense LCP of at most `max_size` pairs (the kinds above; K, or
  // K_c, is factorised to find out). Otherwise false with the reason, naming `formulation`, in
  // *why.
  static bool CanReduce(const std::string& formulation, const StepProblem& step, int max_size,
                        std::string* why);

  // The LCP of `step`. Throws std::invalid_argument when the step does not reduce (CanReduce's
  // reasons, without its size limit), naming the reason. `eliminate` forces the elimination for
  // a linear ComplementarityModel (whose K = M is then factorised; the tests compare both).
  explicit SteppedLcp(const StepProblem& step, bool eliminate = false);
  ~SteppedLcp();

  Kind kind() const { return kind_; }
  static const char* KindName(Kind kind);
  int size() const { return static_cast<int>(q_.size()); }
  int num_rigid_modes() const { return static_cast<int>(rigid_.cols()); }
  // V1 (nc x m), the basis of the rigid gaps the LCP is written in (empty without rigid modes).
  const Mat& rigid_basis() const { return rigid_; }
  // delta, by which both rows of each rigid equality are relaxed (0 without rigid modes).
  double rigid_relaxation() const { return relaxation_; }
  // delta = kRigidRelaxation max(1, |e / R|_inf).
  static constexpr double kRigidRelaxation = 1e-12;
  // Column-major n x n, the storage Siconos's dense NumericsMatrix takes.
  const Mat& m() const { return m_; }
  const Vec& q() const { return q_; }

  // z^ of a point of the step (a start: the increment and the reactions), clipped at 0; the
  // rigid amplitudes a+^ = a-^ = 0.
  Vec ZFromPoint(const Vec& du, const Vec& r) const;
  // The step's point (physical units) from z^: du, g from the model at u^k + du, r, dlambda.
  StepPoint PointFromZ(const Vec& z) const;

  // The basis of the rigid gaps given any orthonormal basis `v1` (nc x m) of them: the
  // projections v1 v1^T X of fixed reference vectors X (nc x m, pseudo-random from a fixed seed),
  // orthonormalised in order by QR with R's diagonal positive. It depends on the span of v1 only
  // (v1 Q gives the same for any orthogonal Q), and moves with it as little as the projector
  // does: a perturbation of A moves the eigensolver's basis of a multiple eigenvalue by its size
  // over the eigenvalues' spread, this one by its size over the gap to the elastic ones.
  static Mat CanonicalRigidBasis(const Mat& v1);

 private:
  void BuildAsGiven();
  void BuildEliminated();

  const StepProblem& step_;
  Kind kind_ = Kind::kAsGiven;
  Mat m_;
  Vec q_;
  // Elimination only, to recover du from z^ (one more solve): the factorisation of K (or K_c),
  // G, c, b - c G^T phi(u^k), and V1 (nc x m).
  struct Factor;
  std::unique_ptr<Factor> factor_;
  SpMat g_;
  double penalty_ = 0.0;
  Vec rhs_;
  Mat rigid_;
  double relaxation_ = 0.0;
};

}  // namespace cb
