// The "cholmod" linear solver: a Jacobian with the block structure of JacobianStructure
// (equation_system.h) is condensed to a symmetric system in v alone, factorised by CHOLMOD
// (supernodal Cholesky where it pays, AMD / METIS ordering), and the border rows and columns
// (y: dlambda, rho) are eliminated by block elimination with a few extra solves.
//
// Condensation, exact: (R2) gives g = E^-1 (b2 - G v); (R3) gives r = Db^-1 (b3 - Da g - U3 y);
// substituted into (R1),
//   Kc v + B y = h1,    Kc = A + G^T diag(w) G,   w = -coupling Da / (E Db),
//   B = U1 - H Db^-1 U3,  h1 = b1 - H Db^-1 (b3 - Da E^-1 b2),
// and the border rows become C^T v + Wc y = h4 (small dense m x m Schur complement). For the
// smoothed FB rows Da <= 0 <= Db, so w >= 0 and Kc is symmetric positive (semi)definite: the
// stiffness plus a spring per contact pair. Where Db -> 0 (a closed pair as rho -> 0; exactly 0
// for the nonsmooth rows) w blows up: w is capped at kPenaltyCap times the stiffness on that
// pair's dofs, which replaces Db by a slightly larger value, and the answer is made exact by
// iterative refinement on the FULL system (residual with the original matrix, correction by
// the condensed solve): each sweep contracts the error by about (stiffness / spring) ~ 1e-8.
// The refinement also absorbs the rounding of large springs and the one-ulp asymmetry of
// G^T diag(w) G against H diag(.) G.
//
// Fallback (the "klu" full-system LU): a small system (d < 1000, where the LU's refactorisation
// is faster than the condensation's fixed costs), no structure given, a pattern without the
// block form, a Kc that is not positive definite (a tangent stiffness past a limit point, the
// kink row's negative spring), a degenerate pair (Da = Db = 0), a singular border, or a
// refinement that does not reach kAcceptBackwardError. The answer is then the LU's.
#pragma once

#include <memory>

#include "solvers/linear_solver.h"

namespace cb {

// What the condensed solver did (for tests and benchmarks).
struct CondensedSolverStats {
  int condensed_factorizations = 0;  // numeric factorisations of Kc
  int contact_block_factorizations = 0;  // of them, by the dense contact block M alone
  int fallback_factorizations = 0;   // factorisations handed to the full-system LU
  int capped_pairs = 0;              // pairs whose spring was capped, last factorisation
  int refinement_sweeps = 0;         // total refinement sweeps over all solves
  int fallback_solves = 0;           // solves whose refinement failed (then solved by the LU)
  double last_backward_error = 0.0;  // ||b - J x||_inf / (||J||_inf ||x||_inf + ||b||_inf)
};

// A condensed Cholesky solver with `fallback` for the cases it cannot take.
std::unique_ptr<LinearSolver> MakeCondensedCholeskySolver(std::unique_ptr<LinearSolver> fallback);

// The statistics of a solver made by MakeCondensedCholeskySolver, nullptr for any other.
const CondensedSolverStats* CondensedStats(const LinearSolver& solver);

}  // namespace cb
