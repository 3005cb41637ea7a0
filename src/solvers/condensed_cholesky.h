// The "cholmod" linear solver: a Jacobian with the block structure of JacobianStructure
// (equation_system.h) is condensed to a symmetric system in v alone, factorised by CHOLMOD, and
// the border rows and columns (y: dlambda, rho) are eliminated by block elimination with a few
// extra solves (condensed_system.h). What this solver decides is when to trust that.
//
// Where a pair's spring is capped the condensed solve is exact only for a slightly changed
// matrix; the answer is made exact by iterative refinement on the FULL system (residual with the
// original matrix, correction by the condensed solve): each sweep contracts the error by about
// (stiffness / spring) ~ 1e-8. The refinement also absorbs the rounding of large springs and the
// one-ulp asymmetry of G^T diag(w) G against H diag(.) G.
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
  int condensed_factorizations = 0;      // numeric factorisations of Kc
  int contact_block_factorizations = 0;  // of them, by the dense contact block M alone
  int fallback_factorizations = 0;       // factorisations handed to the full-system LU
  int capped_pairs = 0;                  // pairs whose spring was capped, last factorisation
  int refinement_sweeps = 0;             // total refinement sweeps over all solves
  int fallback_solves = 0;               // solves whose refinement failed (then solved by the LU)
  double last_backward_error = 0.0;      // ||b - J x||_inf / (||J||_inf ||x||_inf + ||b||_inf)
};

// A condensed Cholesky solver with `fallback` for the cases it cannot take.
std::unique_ptr<LinearSolver> MakeCondensedCholeskySolver(std::unique_ptr<LinearSolver> fallback);

// The statistics of a solver made by MakeCondensedCholeskySolver, nullptr for any other.
const CondensedSolverStats* CondensedStats(const LinearSolver& solver);

}  // namespace cb
