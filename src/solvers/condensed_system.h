// The condensed form of a step Jacobian J in block form (jacobian_blocks.h): the linear system
// J x = b reduced to a symmetric system in v alone plus the few border unknowns y.
//
// Condensation, exact: (R2) gives g = E^-1 (b2 - G v); (R3) gives r = Db^-1 (b3 - Da g - U3 y);
// substituted into (R1),
//   Kc v + B y = h1,    Kc = A + G^T diag(w) G,   w = -coupling Da / (E Db),
//   B = U1 - H Db^-1 U3,  h1 = b1 - H Db^-1 (b3 - Da E^-1 b2),
// and the border rows become C^T v + Wc y = h4 (small dense m x m Schur complement). For the
// smoothed FB rows Da <= 0 <= Db, so w >= 0 and Kc is symmetric positive (semi)definite: the
// stiffness plus a spring per contact pair. Where Db -> 0 (a closed pair as rho -> 0; exactly 0
// for the nonsmooth rows) w blows up: w is capped at kPenaltyCap times the stiffness on that
// pair's dofs, which replaces Db by a slightly larger value Db~. A solve is then exact for J
// with Db~ in place of Db; the caller refines on the full system (condensed_cholesky.h).
//
// Kc is factorised by CHOLMOD (supernodal Cholesky where it pays, AMD / METIS ordering), whole,
// or by the contact-block update (contact_block_factor.h) when the pairs act on few dofs; the
// border is eliminated by block elimination with a few extra solves.
#pragma once

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <Eigen/LU>
#include <vector>

#include "core/sparse.h"
#include "core/types.h"
#include "solvers/cholmod_wrappers.h"
#include "solvers/contact_block_factor.h"
#include "solvers/jacobian_blocks.h"

namespace cb {

class CondensedSystem {
 public:
  // Takes the blocks of a new Jacobian pattern; Kc's pattern is built, and analysed afresh
  // when it changed.
  void Analyse(JacobianBlocks blocks);
  // Condenses J at its values `values` (J has the analysed pattern; H = -coupling G^T) and
  // factorises Kc and the border's Schur complement. False where the condensation does not
  // apply: H not -coupling G^T, a degenerate pair (E = 0 or Da = Db = 0), a huge negative
  // spring, a Kc that is not positive definite, a singular border.
  bool Factorize(const double* values, double coupling);
  // x = J~^-1 b, J~ the J of the last Factorize (values `values`) with Db~ in place of Db.
  bool Solve(const double* values, const Vec& b, Vec* x);

  // Of the last Factorize: how many pairs had their spring capped, and whether Kc was factorised
  // by the contact-block update.
  int capped_pairs() const { return capped_pairs_; }
  bool used_contact_block() const { return contact_block_active_; }
  int num_analyses() const { return num_analyses_ + contact_block_.num_analyses(); }
  // Whether the last Factorize failed because an interrupt abandoned a factorisation of Kc,
  // whole or by the contact block (interruptible_cholmod.h, dense_cholesky.h).
  bool interrupted() const { return interrupted_; }

 private:
  // w, E, Da / E and Db~ per pair; false where the condensation does not apply.
  bool CondensePairs(const double* values, double coupling);
  // Kc assembled and factorised by CHOLMOD with its own ordering.
  bool FactorizeWhole(const double* values);
  // B, C, Wc, and the Schur complement Wc - C^T Kc^-1 B factorised.
  bool FactorizeBorder(const double* values);
  // x = Kc^-1 b (b: d x cols, column-major) by the whole factor.
  bool SolveWhole(const double* b, int cols, double* x);
  bool SolveWhole(const Mat& b, Mat* x);
  bool SolveWhole(const Vec& b, Vec* x);
  // h4 = b4 - Vg E^-1 b2 - Vr t (t = Db~^-1 (b3 - Da E^-1 b2)), the part of the border's
  // right-hand side that does not depend on v.
  Vec BorderRightHandSide(const Vec& b) const;

  Cholmod cholmod_;  // first: it outlives the factors below
  JacobianBlocks blocks_;

  // Kc's lower triangle: its pattern (which tells a change) with its values, and where the
  // contributions land (A's lower triangle in blocks_ order, then the springs pair by pair).
  SpMat kc_;
  std::vector<int> kc_slots_;
  CholmodFactor whole_factor_;
  CholmodDense whole_solve_buffer_{cholmod_.common()};
  ContactBlockFactor contact_block_{&cholmod_};
  bool contact_block_active_ = false;  // the last Factorize used the contact-block update
  int num_analyses_ = 0;               // of Kc whole
  bool interrupted_ = false;           // the last Factorize was abandoned on an interrupt

  // The pairs at the last Factorize.
  std::vector<double> pair_spring_;  // w
  std::vector<double> e_;            // E
  std::vector<double> da_over_e_;    // Da / E
  std::vector<double> db_capped_;    // Db~
  int capped_pairs_ = 0;

  // The border at the last Factorize: U3 (nc x m), Vg^T and Vr^T (nc x m), B and C (d x m),
  // Z = Kc^-1 B (whole factor), and the LU of Wc - C^T Kc^-1 B.
  Mat u3_, vg_transposed_, vr_transposed_, border_b_, border_c_, kc_inverse_b_;
  Eigen::FullPivLU<Mat> border_schur_lu_;
  // With the contact-block update: Lt^-1 P B and Lt^-1 P C, Dt^-1 Lt^-1 P B, and the forward
  // solve of U1 (the load column) with the U1 and the factor generation it belongs to.
  Mat forward_b_, forward_c_, scaled_forward_b_;
  Mat forward_u1_, forward_u1_of_;
  int forward_u1_generation_ = -1;

  // Work storage of Solve.
  Vec h1_, v_, pair_t_;
  Mat forward_h_, backward_h_;
};

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
