// The step equations on the contact unknowns alone, for a body whose stiffness keeps its values
// (docs/method.md, "Reduced Newton"): the interior rows of (29) / R are linear in du and are
// eliminated once per solve (interior_elimination.h), so that Newton iterates on
//   z = (du_c, g^, r^[, rho])
// with the rows
//   R1 = b~_c + (A_cc + T) du_c - grad phi_c^T r^      (29) / R on the contact dofs, condensed
//   R2, R3[, R4] = (30) / L, the complementarity rows[, the extra row] as in the full system.
// The interior du_i = -A_ii^-1 (b_i + A_ic du_c) is implicit in every iterate, so the interior
// rows of (29) hold at each one to rounding, and it is recovered once at the end. Fixed-load
// steps only: dlambda is then the start's (the constraint row is linear and the start satisfies
// it), and no other row depends on du_i. Every row is evaluated through the full system at the
// lifted point (du_c, du_i = 0, g^, r^, dlambda0[, rho]), where the contact rows of (29) read
// b_c + A_cc du_c - grad phi_c^T r^; the condensation adds b~_c - b_c + T du_c.
#pragma once

#include <string>
#include <vector>

#include "formulations/common/step_equations.h"
#include "solvers/interior_elimination.h"

namespace cb {

// Where a reduced solve spends its time (wall seconds): the pieces of the floor of
// docs/findings.md, "Speed to the floor" (one factorisation, one sweep each way).
struct ReducedStepTimes {
  double factorization_s = 0.0;   // the elimination's factorisation of A + D0 (and T)
  double forward_sweep_s = 0.0;   // Condense: b~_c
  double backward_sweep_s = 0.0;  // Recover: the interior of the answer
};

class ReducedStepSystem final : public EquationSystem {
 public:
  // Whether the reduction applies to `step`; otherwise `why` says why, naming `option` (the
  // formulation's option that asked for it).
  static bool Applies(const StepProblem& step, const std::string& option, std::string* why);

  explicit ReducedStepSystem(StepEquationSystem& full);
  // Eliminates the interior at the full start x0: one Jacobian of the full system, the
  // factorisation and the condensed right-hand side (one forward sweep). False when the
  // elimination fails (A_ii not positive definite).
  bool Prepare(const Vec& x0);
  // z from a full x (its interior du dropped).
  Vec Reduce(const Vec& x) const;
  // The full x of z: the interior recovered (one backward sweep), dlambda the start's.
  bool Expand(const Vec& z, Vec* x);

  int size() const override { return static_cast<int>(kept_rows_.size()); }
  bool Residual(const Vec& z, Vec* residual) override;
  void Jacobian(const Vec& z, SpMat* jacobian) override;
  bool ResidualAndJacobian(const Vec& z, Vec* residual, SpMat* jacobian) override;
  bool shares_residual_and_jacobian() const override { return true; }
  bool ResidualFloor(const Vec& z, Vec* floor) override;
  const JacobianStructure* structure() const override { return &structure_; }

  int num_contact_dofs() const { return static_cast<int>(contact_dofs_.size()); }
  const InteriorElimination& elimination() const { return elimination_; }
  const ReducedStepTimes& times() const { return times_; }

 private:
  // lifted_ from z.
  void Lift(const Vec& z);
  // The reduced rows from the full residual full_residual_ at lifted_.
  void ReduceResidual(const Vec& z, Vec* residual) const;
  // The reduced pattern and where the full Jacobian's entries and T land in it.
  void BuildPattern(const SpMat& full_jacobian);
  void ReduceJacobian(SpMat* jacobian) const;

  StepEquationSystem& full_;
  InteriorElimination elimination_;
  JacobianStructure structure_;
  std::vector<int> contact_dofs_;
  std::vector<int> kept_rows_, kept_cols_;    // full index per reduced row / unknown
  Vec x0_, lifted_, full_residual_, offset_;  // offset_ = b~_c - b_c
  SpMat full_jacobian_, pattern_;
  std::vector<std::pair<int, int>> entry_slots_;  // (full slot, reduced slot)
  std::vector<int> correction_slots_;             // T(a, b) at [b * c + a]
  ReducedStepTimes times_;
};

// RunStepEquationSolver (step_equations.h) through the reduced system of `system` from the full
// start *x; *x is the full answer. details["route"] = "reduced", and the time split in seconds:
// details "prepare_s" (the first Jacobian, the factorisation, b~_c), "factorization_s",
// "forward_sweep_s", "iterations_s", "recovery_s", "backward_sweep_s".
SolverSummary RunReducedStepSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                   const SolveControls& controls, StepResult* result);

// The reduced solve, and where it did not end at a point whose full rows hold (each
// |F_i| <= max(residual_tol, its rounding floor): a failure, a limit, or the interior's rounding
// of a badly scaled body), the full route from the same start in the time left, its counts
// added to the reduced solve's (its history numbered on from them) and the reason in its message;
// details["route"] = "full after reduced" then. An interrupted or timed-out reduced solve is
// returned as it is.
SolverSummary RunReducedOrFullStepSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                         const SolveControls& controls, double residual_tol,
                                         StepResult* result);

}  // namespace cb
