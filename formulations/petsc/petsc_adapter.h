// The adapter between the PETSc formulations (petsc_vi_formulation.cc) and PETSc: one SNESVI
// kept across the steps of a path, one run of it on the MCP of petsc_mcp.h, PETSc's counters,
// and SNESConvergedReason mapped onto StepResult; PETSc's process (started once, its errors
// recorded) is petsc_process.h's, the callbacks' glue shared with the distributed backend
// snes_glue.h's. Built only when PETSc is found (petsc.cmake; petsc_stub.cc otherwise).
//
// The options. PETSc's options database is the interface: each formulation instance inserts,
// under an option prefix of its own ("cb<k>_"), its defaults and then the user's string (the
// backend option `petsc_options`, the CLI's --petsc-options), so the user's settings win and
// never reach another instance. The defaults, and why:
//   -snes_type vinewtonrsls | vinewtonssls   the formulation;
//   -ksp_type preonly -pc_type lu   a direct solve, as every suite formulation has;
//   -pc_factor_mat_solver_type umfpack (RSLS) | mumps (SSLS)
//                        the fastest of the factorisations Debian's PETSc offers (MUMPS,
//                        UMFPACK, SuperLU, KLU; PETSc's own LU meets the zero pivots of the
//                        complementarity rows) for each method (docs/backend-petsc.md): RSLS
//                        factorises a new reduced matrix at every iteration, where UMFPACK's
//                        analysis is the cheaper; SSLS keeps one pattern, whose MUMPS analysis
//                        PETSc reuses;
//   -snes_atol 1e-10 -snes_rtol 0
//                        the equation formulations' residual_tol on the scaled rows, here on
//                        the 2-norm SNESVI's test uses (of the inactive rows, RSLS; of the FB
//                        merit, SSLS); no relative test, which would stop a cold start early;
//   -snes_max_it 200     the equation solvers' iteration limit.
// SNESVI's own convergence test (PETSc keeps it internal) is written out in
// SnesViConvergenceTest, with the controls added: SolveControls' interrupt and time limit stop
// the run there, between iterations, with a status (nothing is thrown through PETSc).
//
// The Jacobian is an AIJ matrix preallocated (MatSeqAIJSetPreallocationCSR) with the pattern of
// the step equations' cached ScatterPattern (common/step_equations.h) and
// MAT_NEW_NONZERO_ALLOCATION_ERR on; each evaluation writes its values straight into the AIJ
// storage through McpRowMap. The SNES, the matrix and the
// vectors are kept by the formulation and remade only when the size or the pattern changes
// (another model, constraint kind or kink pair), so along a path the pattern is set once.
//
// Counts: iterations SNESGetIterationNumber, residual_evals SNESGetNumberFunctionEvals,
// jacobian_evals the Jacobian callbacks, linear_solves SNESGetLinearSolveIterations (one per
// solve with preonly; Krylov iterations with an iterative -ksp_type). Exceptions thrown in a
// callback are caught there, the callback returns an error code (which unwinds SNESSolve) and
// the exception is rethrown after SNESSolve returns.
#pragma once

#include <petscsnes.h>

#include <memory>
#include <string>

#include "formulations/common/config.h"
#include "formulations/petsc/petsc_mcp.h"
#include "formulations/petsc/petsc_process.h"
#include "step/formulation.h"

namespace cb {

// The options prefix ("<family><k>_") under which the options text `options` goes into PETSc's
// options database: the same for the same text, so that instances made again and again (a
// benchmark's repetitions, a path's formulations) overwrite their entries instead of adding
// new ones to a database of fixed size (PETSc 3.18 holds 512 entries, then refuses).
std::string OptionsPrefixFor(const std::string& family, const std::string& options);

// The status of a SNESConvergedReason; its PETSc name ("CONVERGED_FNORM_ABS").
Status MapSnesReason(SNESConvergedReason reason);
std::string SnesReasonName(SNESConvergedReason reason);

// After SNESSolve: `result`'s counts from PETSc's counters (`jacobian_evals` the callbacks'),
// details petsc_reason and petsc_options, and status and message ("<label>: <reason>"), or,
// when the run was `stopped` by the controls, kTimeLimit / kStoppedByCaller with the iteration.
struct SnesStop {
  bool stopped = false;
  bool timed_out = false;
  double time_limit_s = 0.0;
};
void RecordSnesOutcome(SNES snes, int jacobian_evals, const std::string& options,
                       const std::string& label, const SnesStop& stop, StepResult* result);

// The defaults of the top of the file for `snes_type`, then `user` (PETSc's option syntax).
std::string PetscViOptions(const std::string& snes_type, const std::string& user);

// One SNESVI of `snes_type` with its options (see the top of the file), kept across solves.
class SnesVi {
 public:
  // Throws std::invalid_argument naming the option PETSc refuses (a bad value, a bad type).
  SnesVi(const std::string& snes_type, const std::string& user_options);
  ~SnesVi();
  SnesVi(const SnesVi&) = delete;
  SnesVi& operator=(const SnesVi&) = delete;

  const std::string& options() const { return options_; }

  // Solves the MCP of `system` within `bounds` from *x (inside them), leaving the last iterate
  // in *x; fills `result`'s status, message, counts, history and details (not its point).
  void Solve(McpStepEquations& system, const McpBounds& bounds, const SolveControls& controls,
             Vec* x, StepResult* result);

 private:
  struct Objects;
  std::string options_;
  std::string user_options_;  // checked for options PETSc never read after the first solve
  bool options_checked_ = false;
  std::unique_ptr<Objects> objects_;
};

}  // namespace cb
