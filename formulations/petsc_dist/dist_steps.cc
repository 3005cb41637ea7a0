#include "formulations/petsc_dist/dist_steps.h"

#include <petscsnes.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <set>
#include <stdexcept>
#include <vector>

#include "core/timer.h"
#include "formulations/petsc/petsc_adapter.h"
#include "formulations/petsc_dist/element_partition.h"
#include "formulations/petsc_dist/field_split.h"
#include "formulations/petsc_dist/parallel_libraries.h"
#include "formulations/petsc_dist/petsc_dist.h"
#include "model/body_contact_model.h"

namespace cb {

bool DistAvailable() { return true; }

namespace {

bool PetscRunning() {
  PetscBool initialized = PETSC_FALSE, finalized = PETSC_FALSE;
  PetscInitialized(&initialized);
  PetscFinalized(&finalized);
  return initialized && !finalized;
}

// Whether any process says so (a decision every process then takes).
bool AnyProcess(bool mine) {
  int local = mine ? 1 : 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return any != 0;
}

// Several processes need MPI's own functions and the parallel MUMPS (parallel_libraries.h);
// the driver relaunches itself with them first, so a stand-in left serving is refused.
void RequireParallelLibraries() {
  const std::string library = SequentialStandIn();
  if (library.empty()) return;
  throw std::invalid_argument(
      "a run of several processes needs MPI and MUMPS, which this build's sequential MUMPS (" +
      library +
      ", linked by the Ipopt or Siconos backend) stands in for, and loading the parallel ones "
      "first (LD_PRELOAD) did not help; configure a build with -DCONTACTBENCH_WITH_IPOPT=OFF "
      "-DCONTACTBENCH_WITH_SICONOS=OFF (docs/scale-out.md)");
}

// The partition Objects::Make last made, and of which body (ElementsOfEachProcess).
struct LastPartition {
  const ElasticBody* body = nullptr;
  std::vector<std::vector<int>> parts;
};
LastPartition& Partitioned() {
  static LastPartition last;
  return last;
}

}  // namespace

std::vector<std::vector<int>> ElementsOfEachProcess(const ElasticBody& body) {
  const LastPartition& last = Partitioned();
  if (last.body != &body) return {};
  std::size_t elements = 0;
  for (const auto& part : last.parts) elements += part.size();
  // Another body made at the address of a destroyed one is told apart by its element count.
  if (elements != body.Cells().size()) return {};
  return last.parts;
}

int DistributedRank() {
  if (!PetscRunning()) return 0;
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

int DistributedSize() {
  if (!PetscRunning()) return 1;
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

bool CanDistribute(const StepProblem& step, std::string* why) {
  if (dynamic_cast<const BodyContactModel*>(step.model) != nullptr) return true;
  if (why != nullptr) *why = "the distributed formulations need a body against obstacles";
  return false;
}

// --- the objects of one instance ---------------------------------------------------------------

struct DistributedSteps::Objects {
  SNES snes = nullptr;
  ::Vec x = nullptr, f = nullptr, all = nullptr, lower = nullptr, upper = nullptr;
  VecScatter to_all = nullptr;
  ::Mat jacobian = nullptr;
  PetscInt first = 0, last = 0;  // this process's rows [first, last)

  // What the objects were made for, and the contact-only model of contact_model_of.
  const ContactModel* model = nullptr;
  const ContactModel* contact_model_of = nullptr;
  int size = 0;
  std::shared_ptr<const BodyContactModel> contact_only;
  std::shared_ptr<const ElasticBody> own;  // this process's elements
  std::vector<PetscInt> own_dofs;          // the rows its elements touch, ascending
  StepProblem contact_only_step;

  // One solve's context for the callbacks.
  const StepProblem* step = nullptr;
  const LocalStepEquations* equations = nullptr;
  const SolveControls* controls = nullptr;
  StepResult* result = nullptr;
  Stopwatch clock;
  double residual_tol = 0.0;
  bool vi = false;
  bool stopped = false, timed_out = false;
  int jacobian_evals = 0;
  std::exception_ptr error;
  Vec full, local_f, element_force;
  SpMat local_jacobian, element_stiffness;

  void DestroyOperands() {
    VecScatterDestroy(&to_all);
    VecDestroy(&all);
    VecDestroy(&x);
    VecDestroy(&f);
    VecDestroy(&lower);
    VecDestroy(&upper);
    MatDestroy(&jacobian);
    model = nullptr;
  }

  // The vectors, the partition and the models for `model` and a system of `n` rows.
  void Make(const StepProblem& s, int n) {
    DestroyOperands();
    Try(SNESReset(snes), "SNESReset");
    Try(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, n, &x), "VecCreateMPI");
    Try(VecDuplicate(x, &f), "VecDuplicate");
    Try(VecGetOwnershipRange(x, &first, &last), "VecGetOwnershipRange");
    Try(VecScatterCreateToAll(x, &to_all, &all), "VecScatterCreateToAll");
    const PetscInt* ranges = nullptr;
    Try(VecGetOwnershipRanges(x, &ranges), "VecGetOwnershipRanges");
    std::vector<int> starts(static_cast<std::size_t>(DistributedSize()) + 1);
    for (std::size_t k = 0; k < starts.size(); ++k) starts[k] = static_cast<int>(ranges[k]);

    const ElasticBody& body = dynamic_cast<const BodyContactModel&>(*s.model).body();
    const auto parts = PartitionElements(body, starts);
    own = body.Restricted(parts[static_cast<std::size_t>(DistributedRank())]);
    Partitioned() = {&body, parts};
    std::set<PetscInt> touched;
    for (const auto& cell : own->Cells()) {
      for (int node : cell) {
        for (int c = 0; c < body.dim(); ++c) {
          if (body.dofs().dof(node, c) >= 0) touched.insert(body.dofs().dof(node, c));
        }
      }
    }
    own_dofs.assign(touched.begin(), touched.end());
    model = s.model;
    size = n;
    if (!vi) SplitWhereAsked(dynamic_cast<const BodyContactModel&>(*s.model));
  }

  // A field-split preconditioner (chosen by the options) gets the du rows and the rest (SNESReset
  // above has cleared the splits of an earlier model). SNESVI solves on reduced rows: not there.
  void SplitWhereAsked(const BodyContactModel& model) const {
    KSP ksp = nullptr;
    PC pc = nullptr;
    PetscBool split = PETSC_FALSE, shell = PETSC_FALSE;
    Try(SNESGetKSP(snes, &ksp), "SNESGetKSP");
    Try(KSPGetPC(ksp, &pc), "KSPGetPC");
    Try(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCFIELDSPLIT, &split),
        "PetscObjectTypeCompare");
    Try(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCSHELL, &shell),
        "PetscObjectTypeCompare");
    if (split) Try(SetDisplacementSplit(pc, model.body(), first, last), "PCFieldSplitSetIS");
    if (shell) Try(SetAugmentedSplit(pc, model, first, last), "SetAugmentedSplit");
  }

  // The iterate of `v` on every process, into `full`.
  void Gather(::Vec v) {
    Try(VecScatterBegin(to_all, v, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    Try(VecScatterEnd(to_all, v, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* a = nullptr;
    Try(VecGetArrayRead(all, &a), "VecGetArrayRead");
    full = Eigen::Map<const Vec>(a, size);
    Try(VecRestoreArrayRead(all, &a), "VecRestoreArrayRead");
  }

  // This process's rows of a full vector into `v`.
  void Scatter(const Vec& from, ::Vec v) const {
    PetscScalar* a = nullptr;
    Try(VecGetArrayWrite(v, &a), "VecGetArrayWrite");
    std::copy_n(from.data() + first, last - first, a);
    Try(VecRestoreArrayWrite(v, &a), "VecRestoreArrayWrite");
  }

  Vec Displacement() const { return step->base.u + full.head(equations->layout.d); }

  // F: the local rows on this process's rows, the elements' share of (29) / R added.
  bool Residual(::Vec out) {
    const bool finite = equations->residual(full, &local_f);
    Scatter(local_f, out);
    own->InternalForce(Displacement(), &element_force);
    std::vector<PetscScalar> values(own_dofs.size());
    for (std::size_t k = 0; k < own_dofs.size(); ++k) {
      values[k] = element_force[own_dofs[k]] / step->scales.force;
    }
    Try(VecSetValues(out, static_cast<PetscInt>(own_dofs.size()), own_dofs.data(), values.data(),
                     ADD_VALUES),
        "VecSetValues");
    return finite;
  }

  // Adds the rows [row_first, row_last) of `m` times `scale` into `target`.
  static void AddRows(const SpMat& m, PetscInt row_first, PetscInt row_last, double scale,
                      ::Mat target) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor, int> rows = m;
    std::vector<PetscInt> columns;
    std::vector<PetscScalar> values;
    for (PetscInt i = row_first; i < row_last; ++i) {
      const int begin = rows.outerIndexPtr()[i], end = rows.outerIndexPtr()[i + 1];
      if (begin == end) continue;
      columns.assign(rows.innerIndexPtr() + begin, rows.innerIndexPtr() + end);
      values.assign(rows.valuePtr() + begin, rows.valuePtr() + end);
      for (auto& v : values) v *= scale;
      Try(MatSetValues(target, 1, &i, end - begin, columns.data(), values.data(), ADD_VALUES),
          "MatSetValues");
    }
  }

  // The local Jacobian's rows of this process and the elements' stiffness / R into `target`.
  void AddJacobian(::Mat target) {
    AddRows(local_jacobian, first, last, 1.0, target);
    AddRows(element_stiffness, 0, element_stiffness.rows(), 1.0 / step->scales.force, target);
  }

  void EvaluateJacobianParts() {
    equations->jacobian(full, &local_jacobian);
    own->Stiffness(Displacement(), &element_stiffness);
  }

  // The MPIAIJ matrix preallocated with the entries of every process (MATPREALLOCATOR).
  void MakeMatrix() {
    ::Mat counter = nullptr;
    auto square = [&](::Mat* m, MatType type) {
      Try(MatCreate(PETSC_COMM_WORLD, m), "MatCreate");
      Try(MatSetSizes(*m, last - first, last - first, size, size), "MatSetSizes");
      Try(MatSetType(*m, type), "MatSetType");
    };
    square(&counter, MATPREALLOCATOR);
    Try(MatSetUp(counter), "MatSetUp");
    AddJacobian(counter);
    AddDiagonal(counter);
    Try(MatAssemblyBegin(counter, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    Try(MatAssemblyEnd(counter, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    square(&jacobian, MATMPIAIJ);
    Try(MatPreallocatorPreallocate(counter, PETSC_TRUE, jacobian), "MatPreallocatorPreallocate");
    MatDestroy(&counter);
    Try(MatSetOption(jacobian, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
  }

  // Every diagonal entry stored (SNESVINEWTONSSLS adds to the diagonal).
  void AddDiagonal(::Mat target) const {
    for (PetscInt i = first; i < last; ++i) {
      Try(MatSetValue(target, i, i, 0.0, ADD_VALUES), "MatSetValue");
    }
  }
};

namespace {

using Objects = DistributedSteps::Objects;

// Runs `body` on every process and agrees on the outcome: false on every process when it threw
// on any (the exception is kept where it was thrown, for Solve to rethrow).
template <typename Body>
bool Agreed(Objects* o, Body&& body) {
  bool failed = static_cast<bool>(o->error);
  if (!failed) {
    try {
      body();
    } catch (...) {
      o->error = std::current_exception();
      failed = true;
    }
  }
  return !AnyProcess(failed);
}

PetscErrorCode EvaluateResidual(SNES snes, ::Vec x, ::Vec f, void* context) {
  auto* o = static_cast<Objects*>(context);
  bool finite = true;
  if (!Agreed(o, [&] {
        o->Gather(x);
        finite = o->Residual(f);
      })) {
    return PETSC_ERR_USER;
  }
  PetscErrorCode code = VecAssemblyBegin(f);
  if (code == 0) code = VecAssemblyEnd(f);
  if (code == 0 && AnyProcess(!finite)) code = SNESSetFunctionDomainError(snes);
  return code;
}

PetscErrorCode EvaluateJacobian(SNES, ::Vec x, ::Mat, ::Mat, void* context) {
  auto* o = static_cast<Objects*>(context);
  if (!Agreed(o, [&] {
        o->Gather(x);
        o->EvaluateJacobianParts();
      })) {
    return PETSC_ERR_USER;
  }
  PetscErrorCode code = MatZeroEntries(o->jacobian);
  if (code != 0) return code;
  if (!Agreed(o, [&] {
        o->AddJacobian(o->jacobian);
        o->AddDiagonal(o->jacobian);
      })) {
    return PETSC_ERR_USER;
  }
  code = MatAssemblyBegin(o->jacobian, MAT_FINAL_ASSEMBLY);
  if (code == 0) code = MatAssemblyEnd(o->jacobian, MAT_FINAL_ASSEMBLY);
  ++o->jacobian_evals;
  return code;
}

// History: merit 1/2 fnorm^2 of SNES's norm, residual_inf ||F||_inf, comp_res of the gathered
// iterate, step_length the line search's lambda.
PetscErrorCode RecordIteration(SNES snes, PetscInt iteration, PetscReal fnorm, void* context) {
  auto* o = static_cast<Objects*>(context);
  ::Vec x = nullptr, f = nullptr;
  PetscReal inf = 0.0, step = 0.0;
  PetscErrorCode code = SNESGetSolution(snes, &x);
  if (code == 0) code = SNESGetFunction(snes, &f, nullptr, nullptr);
  if (code == 0) code = VecNorm(f, NORM_INFINITY, &inf);
  SNESLineSearch line_search = nullptr;
  if (code == 0 && iteration > 0 && SNESGetLineSearch(snes, &line_search) == 0) {
    SNESLineSearchGetLambda(line_search, &step);
  }
  if (code != 0) return code;
  if (!Agreed(o, [&] {
        o->Gather(x);
        IterationRecord record;
        record.iteration = static_cast<int>(iteration);
        record.merit = 0.5 * fnorm * fnorm;
        record.residual_inf = inf;
        record.comp_res = ComplementarityResidual(o->equations->layout, o->full);
        record.step_length = step;
        o->result->history.push_back(record);
      })) {
    return PETSC_ERR_USER;
  }
  return 0;
}

// The stopping test (see the top of the header), then the controls, agreed by all processes.
PetscErrorCode ConvergenceTest(SNES snes, PetscInt iteration, PetscReal, PetscReal, PetscReal fnorm,
                               SNESConvergedReason* reason, void* context) {
  auto* o = static_cast<Objects*>(context);
  PetscReal atol = 0.0, rtol = 0.0, inf = 0.0;
  PetscInt max_its = 0, max_funcs = 0, funcs = 0;
  PetscErrorCode code = SNESGetTolerances(snes, &atol, &rtol, nullptr, &max_its, &max_funcs);
  if (code == 0) code = SNESGetNumberFunctionEvals(snes, &funcs);
  ::Vec f = nullptr;
  if (code == 0 && !o->vi) code = SNESGetFunction(snes, &f, nullptr, nullptr);
  if (code == 0 && !o->vi) code = VecNorm(f, NORM_INFINITY, &inf);
  if (code != 0) return code;
  *reason = SNES_CONVERGED_ITERATING;
  if (std::isnan(fnorm)) {
    *reason = SNES_DIVERGED_FNORM_NAN;
  } else if (o->vi ? fnorm < atol : inf <= o->residual_tol) {
    *reason = SNES_CONVERGED_FNORM_ABS;
  } else if (iteration >= max_its) {
    *reason = SNES_DIVERGED_MAX_IT;
  } else if (max_funcs >= 0 && funcs >= max_funcs) {
    *reason = SNES_DIVERGED_FUNCTION_COUNT;
  }
  if (*reason != SNES_CONVERGED_ITERATING) return 0;
  const SolveControls& c = *o->controls;
  const bool late = c.time_limit_s > 0.0 && o->clock.Seconds() > c.time_limit_s;
  const bool asked = c.interrupted && c.interrupted();
  o->timed_out = AnyProcess(late);
  o->stopped = o->timed_out || AnyProcess(asked);
  if (o->stopped) *reason = SNES_DIVERGED_FUNCTION_COUNT;  // stops SNESSolve; see `stopped`
  return 0;
}

// After a failed evaluation: every process throws, its own exception or word of another's.
[[noreturn]] void RethrowFailure(Objects* o) {
  const std::exception_ptr error = o->error;
  o->DestroyOperands();
  if (error) std::rethrow_exception(error);
  throw std::runtime_error("the step system's evaluation failed on another process");
}

}  // namespace

// --- the instance ------------------------------------------------------------------------------

DistributedSteps::DistributedSteps(const std::string& defaults, const std::string& user_options)
    : options_(user_options.empty() ? defaults : defaults + " " + user_options),
      objects_(std::make_unique<Objects>()) {
  StartPetsc();
  if (DistributedSize() > 1) RequireParallelLibraries();
  PetscErrorCapture capture;
  const std::string prefix = OptionsPrefixFor("cbd", options_);
  Try(PetscOptionsPrefixPush(nullptr, prefix.c_str()), "PetscOptionsPrefixPush");
  const PetscErrorCode inserted = PetscOptionsInsertString(nullptr, options_.c_str());
  Try(PetscOptionsPrefixPop(nullptr), "PetscOptionsPrefixPop");
  if (inserted != 0) {
    throw std::invalid_argument("petsc_options '" + user_options + "': PETSc refuses them");
  }
  Objects* o = objects_.get();
  Try(SNESCreate(PETSC_COMM_WORLD, &o->snes), "SNESCreate");
  Try(SNESSetOptionsPrefix(o->snes, prefix.c_str()), "SNESSetOptionsPrefix");
  if (SNESSetFromOptions(o->snes) != 0) {
    SNESDestroy(&o->snes);
    throw std::invalid_argument("petsc_options '" + user_options +
                                "': PETSc's SNESSetFromOptions refuses them");
  }
  Try(SNESMonitorSet(o->snes, RecordIteration, o, nullptr), "SNESMonitorSet");
  Try(SNESSetConvergenceTest(o->snes, ConvergenceTest, o, nullptr), "SNESSetConvergenceTest");
}

DistributedSteps::~DistributedSteps() {
  if (!PetscRunning()) return;  // PETSc finalised first (at exit): nothing left to free
  objects_->DestroyOperands();
  SNESDestroy(&objects_->snes);
}

const StepProblem& DistributedSteps::ContactOnlyStep(const StepProblem& step) {
  std::string why;
  if (!CanDistribute(step, &why)) throw std::invalid_argument(why);
  Objects& o = *objects_;
  if (o.contact_model_of != step.model) {
    const auto& model = dynamic_cast<const BodyContactModel&>(*step.model);
    o.contact_only = std::make_shared<BodyContactModel>(
        model.body().Restricted({}), model.obstacles(), model.pairs(), model.load_pattern());
    o.contact_model_of = step.model;
  }
  o.contact_only_step = step;
  o.contact_only_step.model = o.contact_only.get();
  return o.contact_only_step;
}

void DistributedSteps::Solve(const StepProblem& step, const LocalStepEquations& equations,
                             const DistBounds* bounds, double residual_tol,
                             const SolveControls& controls, Vec* x, StepResult* result) {
  PetscErrorCapture capture;
  Objects& o = *objects_;
  const int n = equations.layout.size();
  o.vi = bounds != nullptr;
  if (o.model != step.model || o.size != n) o.Make(step, n);
  o.step = &step;
  o.equations = &equations;
  o.controls = &controls;
  o.result = result;
  o.clock = Stopwatch();
  o.residual_tol = residual_tol;
  o.stopped = o.timed_out = false;
  o.jacobian_evals = 0;
  o.error = nullptr;
  o.Scatter(*x, o.x);
  if (o.jacobian == nullptr) {
    // The pattern of the start's Jacobian, every process's entries counted.
    o.full = *x;
    if (!Agreed(&o, [&] {
          o.EvaluateJacobianParts();
          o.MakeMatrix();
        })) {
      RethrowFailure(&o);
    }
  }
  Try(SNESSetFunction(o.snes, o.f, EvaluateResidual, &o), "SNESSetFunction");
  Try(SNESSetJacobian(o.snes, o.jacobian, o.jacobian, EvaluateJacobian, &o), "SNESSetJacobian");
  if (bounds != nullptr) {
    if (o.lower == nullptr) {
      Try(VecDuplicate(o.x, &o.lower), "VecDuplicate");
      Try(VecDuplicate(o.x, &o.upper), "VecDuplicate");
    }
    auto marked = [](Vec b) {
      for (Eigen::Index i = 0; i < b.size(); ++i) {
        if (std::isinf(b[i])) b[i] = b[i] > 0 ? PETSC_INFINITY : PETSC_NINFINITY;
      }
      return b;
    };
    o.Scatter(marked(bounds->lower), o.lower);
    o.Scatter(marked(bounds->upper), o.upper);
    Try(SNESVISetVariableBounds(o.snes, o.lower, o.upper), "SNESVISetVariableBounds");
  }
  const PetscErrorCode code = SNESSolve(o.snes, nullptr, o.x);
  if (AnyProcess(static_cast<bool>(o.error))) RethrowFailure(&o);
  o.Gather(o.x);
  *x = o.full;

  RecordSnesOutcome(o.snes, o.jacobian_evals, options_, "PETSc SNES",
                    {o.stopped, o.timed_out, controls.time_limit_s}, result);
  result->details["processes"] = std::to_string(DistributedSize());
  if (code != 0) {
    const char* text = nullptr;
    PetscErrorMessage(code, &text, nullptr);
    result->status = Status::kFailed;
    result->message = std::string("PETSc SNESSolve failed: ") + (text != nullptr ? text : "");
    o.DestroyOperands();
  }
}

}  // namespace cb
