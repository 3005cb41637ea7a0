#include "formulations/petsc/petsc_adapter.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "core/timer.h"
#include "formulations/petsc/petsc_unused_options.h"
#include "formulations/petsc/snes_glue.h"

namespace cb {

// --- reasons -----------------------------------------------------------------------------------

Status MapSnesReason(SNESConvergedReason reason) {
  switch (reason) {
    case SNES_CONVERGED_FNORM_ABS:
    case SNES_CONVERGED_FNORM_RELATIVE:
    case SNES_CONVERGED_SNORM_RELATIVE:
      return Status::kConverged;
    case SNES_CONVERGED_ITS:  // the iteration limit with SNESConvergedSkip
    case SNES_DIVERGED_MAX_IT:
    case SNES_DIVERGED_FUNCTION_COUNT:
      return Status::kLimitReached;
    case SNES_CONVERGED_ITERATING:
      return Status::kNotRun;
    default:
      return Status::kFailed;
  }
}

std::string SnesReasonName(SNESConvergedReason reason) {
  return reason >= SNES_DIVERGED_TR_DELTA && reason <= SNES_CONVERGED_ITS
             ? SNESConvergedReasons[reason]
             : "reason " + std::to_string(static_cast<int>(reason));
}

std::string OptionsPrefixFor(const std::string& family, const std::string& options) {
  static std::mutex mutex;
  static std::map<std::string, int> prefixes;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto [it, added] =
      prefixes.emplace(family + '\n' + options, static_cast<int>(prefixes.size()) + 1);
  return family + std::to_string(it->second) + "_";
}

namespace {

// Why SNES stopped, in words; a failed linear solve names the Krylov method's own reason, its
// iteration count and residual (a Krylov failure is not a singular matrix).
std::string SnesOutcomeText(SNES snes, SNESConvergedReason reason) {
  if (reason != SNES_DIVERGED_LINEAR_SOLVE) return SnesReasonName(reason);
  KSP ksp = nullptr;
  KSPConvergedReason ksp_reason = KSP_CONVERGED_ITERATING;
  PetscInt iterations = 0;
  PetscReal residual = 0.0;
  if (SNESGetKSP(snes, &ksp) != 0 || KSPGetConvergedReason(ksp, &ksp_reason) != 0 ||
      KSPGetIterationNumber(ksp, &iterations) != 0 || KSPGetResidualNorm(ksp, &residual) != 0) {
    return SnesReasonName(reason);
  }
  std::ostringstream text;
  text << "the linear solver did not converge in " << iterations << " iterations (residual "
       << residual << ", " << KSPConvergedReasons[ksp_reason] << "; " << SnesReasonName(reason)
       << ")";
  return text.str();
}

}  // namespace

void RecordSnesOutcome(SNES snes, int jacobian_evals, const std::string& options,
                       const std::string& label, const SnesStop& stop, StepResult* result) {
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  PetscInt iterations = 0, funcs = 0, linear = 0;
  SNESGetConvergedReason(snes, &reason);
  SNESGetIterationNumber(snes, &iterations);
  SNESGetNumberFunctionEvals(snes, &funcs);
  SNESGetLinearSolveIterations(snes, &linear);
  result->counts = {static_cast<int>(iterations), static_cast<int>(funcs), jacobian_evals,
                    static_cast<int>(linear)};
  result->details["petsc_reason"] =
      std::to_string(static_cast<int>(reason)) + " " + SnesReasonName(reason);
  result->details["petsc_options"] = options;
  result->status = MapSnesReason(reason);
  result->message = label + ": " + SnesOutcomeText(snes, reason);
  if (stop.stopped) {
    result->status = stop.timed_out ? Status::kTimeLimit : Status::kStoppedByCaller;
    result->message =
        stop.timed_out ? TimeLimitMessage(stop.time_limit_s) : label + ": stopped by the caller";
    result->message += " at iteration " + std::to_string(iterations);
  }
}

std::string PetscViOptions(const std::string& snes_type, const std::string& user) {
  // See the top of the header for the factorisation of each method.
  const std::string factorisation = snes_type == SNESVINEWTONRSLS ? "umfpack" : "mumps";
  std::string options = "-snes_type " + snes_type +
                        " -ksp_type preonly -pc_type lu -pc_factor_mat_solver_type " +
                        factorisation + " -snes_atol 1e-10 -snes_rtol 0 -snes_max_it 200";
  return user.empty() ? options : options + " " + user;
}

// --- one SNESVI --------------------------------------------------------------------------------

namespace {

// What the callbacks of one Solve share.
struct SnesViRun {
  SnesViRun(McpStepEquations& s, const McpBounds& b, const McpRowMap& r, const SolveControls& c,
            StepResult& out)
      : system(s), bounds(b), rows(r), result(out) {
    watch.Start(&c);
  }
  McpStepEquations& system;
  const McpBounds& bounds;
  const McpRowMap& rows;
  StepResult& result;
  SnesControlsWatch watch;
  Vec x, f;
  SpMat jacobian;
  int jacobian_evals = 0;
  double initial_norm = 0.0;
  std::exception_ptr error;
};

void CopyIn(::Vec from, Vec* to) {
  const PetscScalar* a = nullptr;
  PetscInt n = 0;
  VecGetLocalSize(from, &n);
  VecGetArrayRead(from, &a);
  *to = Eigen::Map<const Vec>(a, n);
  VecRestoreArrayRead(from, &a);
}

void CopyOut(const Vec& from, ::Vec to) {
  PetscScalar* a = nullptr;
  VecGetArrayWrite(to, &a);
  std::copy_n(from.data(), from.size(), a);
  VecRestoreArrayWrite(to, &a);
}

// The bounds with PETSc's markers of "no bound" (SNESVI compares against them exactly).
void CopyBound(const Vec& bound, ::Vec to) {
  Vec marked = bound;
  for (Eigen::Index i = 0; i < marked.size(); ++i) {
    if (std::isinf(marked[i])) marked[i] = marked[i] > 0 ? PETSC_INFINITY : PETSC_NINFINITY;
  }
  CopyOut(marked, to);
}

// Runs `body` for a callback; an exception is kept for Solve to rethrow and stops SNESSolve.
template <typename Body>
PetscErrorCode Guard(SnesViRun* run, Body&& body) {
  return Captured(&run->error, body) ? 0 : PETSC_ERR_USER;
}

// F of petsc_mcp.h; a non-finite value is a domain error (the line search then cuts back).
PetscErrorCode EvaluateMcp(SNES snes, ::Vec x, ::Vec f, void* context) {
  auto* run = static_cast<SnesViRun*>(context);
  return Guard(run, [&] {
    CopyIn(x, &run->x);
    const bool finite = McpFunction(run->system, run->x, &run->f);
    CopyOut(run->f, f);
    if (!finite) SNESSetFunctionDomainError(snes);
  });
}

// The MCP Jacobian: the step equations' Jacobian, combined and written into the AIJ storage
// through the row map (petsc_mcp.h).
PetscErrorCode EvaluateJacobian(SNES, ::Vec x, ::Mat, ::Mat jacobian, void* context) {
  auto* run = static_cast<SnesViRun*>(context);
  return Guard(run, [&] {
    CopyIn(x, &run->x);
    run->system.Jacobian(run->x, &run->jacobian);
    if (!SamePattern(run->rows, run->jacobian)) {
      throw std::logic_error("the MCP Jacobian's pattern changed within a solve");
    }
    PetscScalar* values = nullptr;
    Try(MatSeqAIJGetArrayWrite(jacobian, &values), "MatSeqAIJGetArrayWrite");
    FillMcpValues(run->rows, run->jacobian, values);
    Try(MatSeqAIJRestoreArrayWrite(jacobian, &values), "MatSeqAIJRestoreArrayWrite");
    ++run->jacobian_evals;
  });
}

// History: merit 1/2 fnorm^2 of SNESVI's norm, residual_inf the MCP's natural residual,
// comp_res of the scaled pairs, step_length the line search's lambda.
PetscErrorCode RecordIteration(SNES snes, PetscInt iteration, PetscReal fnorm, void* context) {
  auto* run = static_cast<SnesViRun*>(context);
  return Guard(run, [&] {
    ::Vec x = nullptr, f = nullptr;
    Try(SNESGetSolution(snes, &x), "SNESGetSolution");
    Try(SNESGetFunction(snes, &f, nullptr, nullptr), "SNESGetFunction");
    CopyIn(x, &run->x);
    CopyIn(f, &run->f);
    IterationRecord record = SnesIterationRecord(snes, iteration, fnorm);
    record.residual_inf = McpNaturalResidual(run->x, run->f, run->bounds);
    record.comp_res = ComplementarityResidual(run->system.layout(), run->x);
    run->result.history.push_back(record);
  });
}

// SNESVI's default test (SNESConvergedDefault_VI, internal to PETSc): NaN, ||F|| < atol, the
// function-evaluation limit, ||F|| < rtol ||F_0||; then the controls.
PetscErrorCode SnesViConvergenceTest(SNES snes, PetscInt iteration, PetscReal, PetscReal,
                                     PetscReal fnorm, SNESConvergedReason* reason, void* context) {
  auto* run = static_cast<SnesViRun*>(context);
  PetscReal atol = 0.0, rtol = 0.0;
  PetscInt max_funcs = 0, funcs = 0;
  PetscErrorCode code = SNESGetTolerances(snes, &atol, &rtol, nullptr, nullptr, &max_funcs);
  if (code == 0) code = SNESGetNumberFunctionEvals(snes, &funcs);
  if (code != 0) return code;
  if (iteration == 0) run->initial_norm = fnorm;
  // SNESVI checks its iteration limit itself.
  *reason = SnesTestReason({fnorm, fnorm < atol, false, max_funcs >= 0 && funcs >= max_funcs,
                            iteration > 0 && fnorm < rtol * run->initial_norm});
  if (*reason != SNES_CONVERGED_ITERATING) return 0;
  return Guard(run, [&] {
    // Any divergence stops SNESSolve; the watch says why.
    if (run->watch.Stop([](bool mine) { return mine; })) *reason = SNES_DIVERGED_FUNCTION_COUNT;
  });
}

}  // namespace

struct SnesVi::Objects {
  SNES snes = nullptr;
  ::Mat jacobian = nullptr;
  ::Vec x = nullptr, f = nullptr, lower = nullptr, upper = nullptr;
  McpRowMap rows;
  SnesViRun* run = nullptr;  // the Solve in progress (the callbacks' context)

  void DestroyOperands() {
    MatDestroy(&jacobian);
    VecDestroy(&x);
    VecDestroy(&f);
    VecDestroy(&lower);
    VecDestroy(&upper);
  }

  // Vectors of size n and the AIJ matrix with `pattern`, preallocated exactly.
  void Make(const StepEquationLayout& layout, const SpMat& pattern) {
    DestroyOperands();
    rows = MakeMcpRowMap(layout, pattern);
    const PetscInt n = rows.size;
    Try(SNESReset(snes), "SNESReset");
    Try(VecCreateSeq(PETSC_COMM_SELF, n, &x), "VecCreateSeq");
    Try(VecDuplicate(x, &f), "VecDuplicate");
    Try(VecDuplicate(x, &lower), "VecDuplicate");
    Try(VecDuplicate(x, &upper), "VecDuplicate");
    Try(MatCreate(PETSC_COMM_SELF, &jacobian), "MatCreate");
    Try(MatSetSizes(jacobian, n, n, n, n), "MatSetSizes");
    Try(MatSetType(jacobian, MATSEQAIJ), "MatSetType");
    Try(MatSeqAIJSetPreallocationCSR(jacobian, rows.row_start.data(), rows.columns.data(), nullptr),
        "MatSeqAIJSetPreallocationCSR");
    Try(MatSetOption(jacobian, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  }
};

SnesVi::SnesVi(const std::string& snes_type, const std::string& user_options)
    : options_(PetscViOptions(snes_type, user_options)),
      user_options_(user_options),
      objects_(std::make_unique<Objects>()) {
  StartPetsc();
  PetscErrorCapture capture;
  const std::string prefix = OptionsPrefixFor("cb", options_);
  Try(PetscOptionsPrefixPush(nullptr, prefix.c_str()), "PetscOptionsPrefixPush");
  const PetscErrorCode inserted = PetscOptionsInsertString(nullptr, options_.c_str());
  Try(PetscOptionsPrefixPop(nullptr), "PetscOptionsPrefixPop");
  if (inserted != 0) {
    throw std::invalid_argument("petsc_options '" + user_options +
                                "': " + PetscErrorText(inserted, "PetscOptionsInsertString"));
  }
  Try(SNESCreate(PETSC_COMM_SELF, &objects_->snes), "SNESCreate");
  Try(SNESSetOptionsPrefix(objects_->snes, prefix.c_str()), "SNESSetOptionsPrefix");
  const PetscErrorCode read = SNESSetFromOptions(objects_->snes);
  if (read != 0) {
    SNESDestroy(&objects_->snes);  // the destructor does not run for a throwing constructor
    throw std::invalid_argument("petsc_options '" + user_options +
                                "': " + PetscErrorText(read, "SNESSetFromOptions"));
  }
  // After SNESSetFromOptions, so that a user's -snes_monitor stays and ours come last.
  Objects* objects = objects_.get();
  auto context = [](Objects* o) { return static_cast<void*>(o); };
  Try(SNESMonitorSet(
          objects->snes,
          [](SNES s, PetscInt i, PetscReal n, void* c) {
            return RecordIteration(s, i, n, static_cast<Objects*>(c)->run);
          },
          context(objects), nullptr),
      "SNESMonitorSet");
  Try(SNESSetConvergenceTest(
          objects->snes,
          [](SNES s, PetscInt i, PetscReal xn, PetscReal sn, PetscReal fn, SNESConvergedReason* r,
             void* c) {
            return SnesViConvergenceTest(s, i, xn, sn, fn, r, static_cast<Objects*>(c)->run);
          },
          context(objects), nullptr),
      "SNESSetConvergenceTest");
}

SnesVi::~SnesVi() {
  if (PetscGone()) return;  // PETSc finalised first (at exit): nothing left to free
  objects_->DestroyOperands();
  SNESDestroy(&objects_->snes);
}

void SnesVi::Solve(McpStepEquations& system, const McpBounds& bounds, const SolveControls& controls,
                   Vec* x, StepResult* result) {
  PetscErrorCapture capture;
  Objects& o = *objects_;
  SnesViRun run(system, bounds, o.rows, controls, *result);
  // The operands are remade only when the step equations' pattern is not the last one; the
  // pattern comes from their cache, so PETSc's evaluations are the only ones.
  const SpMat& pattern = system.JacobianPattern(*x);
  if (o.x == nullptr || !SamePattern(o.rows, pattern)) o.Make(system.layout(), pattern);
  CopyBound(bounds.lower, o.lower);
  CopyBound(bounds.upper, o.upper);
  CopyOut(*x, o.x);
  o.run = &run;
  auto solve = [&]() -> PetscErrorCode {
    PetscErrorCode code = SNESSetFunction(o.snes, o.f, EvaluateMcp, &run);
    if (code == 0) code = SNESSetJacobian(o.snes, o.jacobian, o.jacobian, EvaluateJacobian, &run);
    if (code == 0) code = SNESVISetVariableBounds(o.snes, o.lower, o.upper);
    if (code == 0) code = SNESSolve(o.snes, nullptr, o.x);
    return code;
  };
  const PetscErrorCode code = solve();
  o.run = nullptr;
  if (run.error) std::rethrow_exception(run.error);
  // After the first solve that iterated (a factorisation's options are read when it first
  // factors), PETSc has read what it will read (petsc_unused_options.h).
  PetscInt iterations = 0;
  if (!options_checked_ && code == 0 && SNESGetIterationNumber(o.snes, &iterations) == 0 &&
      iterations > 0) {
    options_checked_ = true;
    RefuseUnusedPetscOptions(OptionsPrefixFor("cb", options_), user_options_);
  }
  CopyIn(o.x, x);

  RecordSnesOutcome(o.snes, run.jacobian_evals, options_, "PETSc SNESVI", run.watch.stop(), result);
  if (code != 0) {
    // A PETSc failure inside the solve (e.g. the factorisation): the step fails with it, and
    // the operands are remade on the next solve.
    result->status = Status::kFailed;
    result->message = PetscErrorText(code, "SNESSolve");
    o.DestroyOperands();
  }
}

}  // namespace cb
