// The contact-block update of the condensed matrix Kc = A + G^T W G (condensed_system.h) when
// the pairs act on few dofs c. Kc = [A_ii A_ic; A_ci A_cc + G^T W G]. While A keeps its values
// (small deformation: the stiffness is constant), A + D0 (D0 = diag(A) on c, to keep it
// definite) is factorised once with c ordered last, L = [L_ii 0; L_ci L_cc]; then
//   Kc = Lt Dt Lt^T,   Lt = [L_ii 0; L_ci I],   Dt = diag(I, M),   M = L_cc L_cc^T - D0 + G^T W G
// with M dense (c x c), and each new W (a Newton iteration) refactorises only M.
#pragma once

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <vector>

#include "core/sparse.h"
#include "core/types.h"
#include "solvers/cholmod_wrappers.h"
#include "solvers/dense_cholesky.h"
#include "solvers/jacobian_blocks.h"

namespace cb {

class ContactBlockFactor {
 public:
  // `cholmod` must outlive this factor.
  explicit ContactBlockFactor(Cholmod* cholmod) : cholmod_(cholmod) {}

  // Forgets the analysis (Kc has a new pattern).
  void Reset();
  // Finds the contact dofs and, when they are few, analyses Kc with them ordered last (the
  // interior by CHOLMOD's own ordering of A_ii). `kc` holds Kc's lower triangle, `kc_entries`
  // its contributions (A's lower triangle, then the springs) and `kc_slots` where they land.
  void Analyse(const JacobianBlocks& blocks, const std::vector<ScatterPattern::Entry>& kc_entries,
               const std::vector<int>& kc_slots, SpMat* kc);
  // Whether Factorize may be tried: analysed, and A has not changed values since.
  bool possible() const { return possible_; }
  // Whether the last Factorize was abandoned on an interrupt.
  bool interrupted() const { return interrupted_; }
  // Factorises M for the springs `pair_spring` at the Jacobian values `values`, and A + D0 first
  // when it is new (then through `kc`, whose values it overwrites). False when A changed values
  // after its first factorisation (then possible() is false from now on) or a factor is not
  // positive definite, or when an interrupt abandoned a factorisation (then interrupted(); the
  // factor of A + D0 is analysed again before the next one: interruptible_cholmod.h).
  bool Factorize(const JacobianBlocks& blocks, const double* values,
                 const std::vector<double>& pair_spring, const std::vector<int>& kc_slots,
                 SpMat* kc);

  // out = Lt^-1 P b (in the permuted order, c last).
  bool Forward(const Mat& b, Mat* out);
  // Dt^-1 on a permuted block: M^-1 on its rows of c.
  void ApplyMiddleInverse(Mat* v) const;
  // out = P^T Lt^-T w.
  bool Backward(Mat w, Mat* out);

  // The contact dofs, increasing; in the permuted order they are the last ones, in this order.
  const std::vector<int>& contact_dofs() const { return contact_dofs_; }
  // Counts the factorisations of A + D0, so that results of Forward can be kept while it holds.
  int generation() const { return generation_; }
  int num_analyses() const { return num_analyses_; }
  // S_cc = L_cc L_cc^T - D0 = A_cc - A_ci A_ii^-1 A_ic of the last factorisation of A + D0, or
  // nullptr when none holds (interior_elimination.h reads it).
  const Mat* stiffness_schur_complement() const { return factor_holds_ ? &s_cc_ : nullptr; }

 private:
  std::vector<int> InteriorOrdering(const JacobianBlocks& blocks);
  bool AnalyseInOrder(const JacobianBlocks& blocks, SpMat* kc);
  // out = phase `second` of phase `first` of the d x cols block `in` (CHOLMOD solve phases).
  bool TwoPhases(int first, int second, const double* in, int cols, Mat* out);
  // L_cc, read off the supernodes of the factor of A + D0.
  void ReadTrailingFactor();
  int num_contact_dofs() const { return static_cast<int>(contact_dofs_.size()); }

  Cholmod* cholmod_;
  int num_dofs_ = 0;
  std::vector<int> contact_dofs_;
  std::vector<int> permutation_;  // of the analysis: the interior, then c
  bool interrupted_ = false;
  std::vector<int> contact_index_;             // per dof: its place in contact_dofs_, or -1
  std::vector<int> kc_contact_diagonal_slot_;  // per contact dof: Kc's diagonal slot
  bool possible_ = false;
  bool factor_holds_ = false;  // the factor of A + D0 and s_cc_ are those of factored_stiffness_
  std::vector<double> factored_stiffness_;  // A's lower-triangle values in the factor
  Vec diagonal_shift_;                      // D0
  Mat trailing_factor_;                     // L_cc
  Mat s_cc_;                                // L_cc L_cc^T - D0
  DenseCholesky contact_block_;             // M, then its factor
  int generation_ = 0;
  int num_analyses_ = 0;
  CholmodFactor factor_;  // of A + D0, c last
  CholmodDense solve_buffer_1_{cholmod_->common()};
  CholmodDense solve_buffer_2_{cholmod_->common()};
};

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
