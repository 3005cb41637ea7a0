// The interior of a linear body eliminated once for a Newton iteration on the contact
// unknowns alone (docs/method.md, "Reduced Newton"). With the dofs split into the contact dofs
// c (those of the pairs) and the interior i, and A the step Jacobian's stiffness block (constant
// on the rows and columns of i for a body whose stiffness keeps its values), the rows i of
// (29) / R, b_i + A_ii du_i + A_ic du_c = 0, give
//   du_i = -A_ii^-1 (b_i + A_ic du_c),
// and the rows c become b~_c + A_cc du_c + T du_c - grad phi_c^T r^ = 0 with
//   b~_c = b_c - A_ci A_ii^-1 b_i,   T = -A_ci A_ii^-1 A_ic (dense c x c).
// With the contact-block factor (contact_block_factor.h) of A + D0, c last,
// L = [L_ii 0; L_ci L_cc]: T = L_cc L_cc^T - D0 - A_cc, b~_c is the c part of Lt^-1 b (one
// forward sweep) and du = P^T Lt^-T [-(Lt^-1 b)_i; du_c] (one backward sweep), since
// L_ii^-1 A_ic = L_ci^T. Where that factor is not offered (few dofs, many contact dofs, no
// SuiteSparse) A_ii is factorised by a simplicial LDL^T and T formed column by column.
#pragma once

#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

#include "core/types.h"

namespace cb {

class InteriorElimination {
 public:
  InteriorElimination();
  ~InteriorElimination();
  InteriorElimination(const InteriorElimination&) = delete;
  InteriorElimination& operator=(const InteriorElimination&) = delete;

  // Factorises at the step Jacobian `jacobian` (block form of jacobian_blocks.h with d dofs and
  // nc pairs). False when it has not the block form, A_ii is not positive definite, or an
  // interrupt abandoned the contact-block factorisation (then interrupted(); no fall-back is
  // started: interruptible_cholmod.h).
  bool Factorize(const SpMat& jacobian, int num_dofs, int num_pairs);
  // The contact dofs, increasing: the unknowns du_c.
  const std::vector<int>& contact_dofs() const { return contact_dofs_; }
  // T = -A_ci A_ii^-1 A_ic, in the order of contact_dofs().
  const Mat& correction() const { return correction_; }
  // b~_c from the rows b (size d) of (29) / R at du = 0; keeps what Recover needs.
  bool Condense(const Vec& b, Vec* b_tilde);
  // du (size d) from du_c, for the b of the last Condense.
  bool Recover(const Vec& du_c, Vec* du);
  // Whether the contact-block factor is used (else the simplicial fallback).
  bool uses_contact_block() const { return uses_contact_block_; }
  // Whether the last Factorize was abandoned on an interrupt.
  bool interrupted() const { return interrupted_; }

 private:
  struct BlockRoute;  // the contact-block factor's state (SuiteSparse only)
  bool FactorizeByBlock(const SpMat& jacobian, int num_dofs, int num_pairs);
  bool FactorizeSimplicial(const SpMat& jacobian, int num_dofs, int num_pairs);

  std::vector<int> contact_dofs_;
  std::vector<int> interior_dofs_;
  Mat correction_;
  bool uses_contact_block_ = false;
  bool interrupted_ = false;
  std::unique_ptr<BlockRoute> block_;
  // The fallback: A_ii's factor, A_ic (dense) and A_ii^-1 b_i of the last Condense.
  Eigen::SimplicialLDLT<SpMat, Eigen::Lower> interior_factor_;
  Mat a_ic_;
  Vec solved_b_i_;
  // The route by blocks: Lt^-1 b of the last Condense.
  Mat forward_b_;
};

}  // namespace cb
