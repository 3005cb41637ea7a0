#include "formulations/petsc_dist/petsc_dist_adapter.h"

#include <petscsnes.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/timer.h"
#include "formulations/petsc/petsc_adapter.h"
#include "formulations/petsc/petsc_unused_options.h"
#include "formulations/petsc/snes_glue.h"
#include "formulations/petsc_dist/dist_line_search.h"
#include "formulations/petsc_dist/element_partition.h"
#include "formulations/petsc_dist/field_split.h"
#include "formulations/petsc_dist/own_pairs_model.h"
#include "formulations/petsc_dist/parallel_libraries.h"
#include "formulations/petsc_dist/petsc_dist.h"
#include "model/body_contact_model.h"
#include "parallel/processes.h"

namespace cb {

bool DistAvailable() { return true; }

namespace {

bool PetscRunning() {
  PetscBool initialized = PETSC_FALSE, finalized = PETSC_FALSE;
  PetscInitialized(&initialized);
  PetscFinalized(&finalized);
  return initialized && !finalized;
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

}  // namespace

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

  // What the objects were made for: the model, the system's size, and this process's share.
  const ContactModel* model = nullptr;
  int size = 0;
  ElementSplit* element_split = nullptr;              // the run's, told each partition of the body
  bool split_pending = false;                         // SplitWhereAsked not yet run for `model`
  std::shared_ptr<const OwnPairsModel> contact_only;  // its pairs, without elements
  std::shared_ptr<const ElasticBody> own;             // its elements
  StepProblem contact_only_step;
  // The rows this process evaluates (see the top of the header): those of its own range, as a
  // mask, and the others, ascending.
  std::vector<char> evaluates_own_row;
  std::vector<PetscInt> evaluated_remote_rows;
  // The rows its elements touch, in its range and outside it.
  std::vector<PetscInt> element_local_rows, element_remote_rows;
  // What Residual sends to other processes: evaluated_remote_rows, then element_remote_rows.
  std::vector<PetscInt> remote_rows;
  std::vector<PetscScalar> remote_values;
  // The elements' stiffness in compressed-column storage (its slots for AddStiffness).
  ScatterPattern element_pattern;

  // The Jacobian's entries as PETSc's COO lists (MatSetPreallocationCOO), made once per pattern
  // of the local Jacobian: its kept entries (their positions in its storage), the elements'
  // stiffness in storage order, every diagonal entry of this process's rows (SNESVINEWTONSSLS
  // adds to the diagonal), and the kept entries of earlier patterns on this model as zeros (a
  // matrix assembled by insertion keeps every entry it was ever given; so does this one, so that
  // the structure MUMPS factors along a path, and with it the rounding, is that of an insertion
  // assembly). `coo_values` is written in that order at each evaluation.
  std::vector<int> kept_jacobian_positions;
  std::vector<int> local_pattern_outer, local_pattern_inner;   // to recognise the pattern
  std::vector<std::pair<PetscInt, PetscInt>> earlier_entries;  // sorted, unique
  std::vector<std::pair<PetscInt, PetscInt>> kept_entries;
  std::vector<PetscScalar> coo_values;

  // One solve's context for the callbacks.
  const StepProblem* step = nullptr;
  const StepRows* equations = nullptr;
  StepResult* result = nullptr;
  SnesControlsWatch watch;
  double residual_tol = 0.0;
  bool vi = false;
  // The serial Newton's line search, when it is SNES's (no -snes_linesearch_type given).
  std::unique_ptr<DistLineSearch> line_search;
  int jacobian_evals = 0;
  std::exception_ptr error;
  Vec full, displacement, local_f, element_force;
  SpMat local_jacobian;

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

  // The vectors, the partition and the contact-only model for `s` and a system of `n` rows.
  void Make(const StepProblem& s, int n) {
    DestroyOperands();
    Try(SNESReset(snes), "SNESReset");
    Try(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, n, &x), "VecCreateMPI");
    Try(VecDuplicate(x, &f), "VecDuplicate");
    Try(VecGetOwnershipRange(x, &first, &last), "VecGetOwnershipRange");
    Try(VecScatterCreateToAll(x, &to_all, &all), "VecScatterCreateToAll");
    const PetscInt* ranges = nullptr;
    Try(VecGetOwnershipRanges(x, &ranges), "VecGetOwnershipRanges");
    std::vector<int> starts(static_cast<std::size_t>(ProcessCount()) + 1);
    for (std::size_t k = 0; k < starts.size(); ++k) starts[k] = static_cast<int>(ranges[k]);
    const auto rank = static_cast<std::size_t>(ProcessRank());

    const auto& whole = dynamic_cast<const BodyContactModel&>(*s.model);
    const ElasticBody& body = whole.body();
    const auto parts = PartitionElements(body, starts);
    own = body.Restricted(parts[rank]);
    if (element_split != nullptr) element_split->Record(parts, body.Cells().size());
    contact_only = std::make_shared<OwnPairsModel>(
        whole, PartitionPairs(body, whole.pairs(), starts)[rank], first, last);
    element_pattern = ScatterPattern(body.num_dofs(), body.num_dofs(), own->StiffnessEntries());
    SelectRows(whole, n, rank + 1 == starts.size() - 1);
    model = s.model;
    size = n;
    split_pending = true;
    earlier_entries.clear();
    kept_entries.clear();
    local_pattern_outer.clear();
  }

  // The rows of the top of the header: this process's displacement rows, its pairs' nodes' dofs
  // and rows (30) and (31), the scalar rows on the last process; the rows its elements touch.
  void SelectRows(const BodyContactModel& whole, int n, bool last_process) {
    const ElasticBody& body = whole.body();
    const int d = body.num_dofs();
    const int nc = whole.num_pairs();
    std::vector<PetscInt> rows;
    for (PetscInt i = first; i < std::min<PetscInt>(last, d); ++i) rows.push_back(i);
    for (int p : contact_only->own_pairs()) {
      const int node = whole.pairs()[static_cast<std::size_t>(p)].node;
      for (int c = 0; c < body.dim(); ++c) {
        if (body.dofs().dof(node, c) >= 0) rows.push_back(body.dofs().dof(node, c));
      }
      rows.push_back(d + p);
      rows.push_back(d + nc + p);
    }
    if (last_process) {
      for (int i = d + 2 * nc; i < n; ++i) rows.push_back(i);
    }
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    evaluates_own_row.assign(static_cast<std::size_t>(last - first), 0);
    evaluated_remote_rows.clear();
    for (PetscInt i : rows) {
      if (i >= first && i < last) {
        evaluates_own_row[static_cast<std::size_t>(i - first)] = 1;
      } else {
        evaluated_remote_rows.push_back(i);
      }
    }

    std::set<PetscInt> touched;
    for (const auto& cell : own->Cells()) {
      for (int node : cell) {
        for (int c = 0; c < body.dim(); ++c) {
          if (body.dofs().dof(node, c) >= 0) touched.insert(body.dofs().dof(node, c));
        }
      }
    }
    element_local_rows.clear();
    element_remote_rows.clear();
    for (PetscInt i : touched)
      (i >= first && i < last ? element_local_rows : element_remote_rows).push_back(i);
    remote_rows = evaluated_remote_rows;
    remote_rows.insert(remote_rows.end(), element_remote_rows.begin(), element_remote_rows.end());
    remote_values.assign(remote_rows.size(), 0.0);
  }
  // A field-split preconditioner (chosen by the options) gets the du rows and the rest (SNESReset
  // in Make has cleared the splits of an earlier model). SNESVI solves on reduced rows: not there.
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

  // u = u^k + du of the gathered iterate, into `displacement`.
  void UpdateDisplacement() { displacement = step->base.u + full.head(equations->layout.d); }

  // F on the rows this process evaluates, the elements' share of (29) / R added: its own rows
  // written in place, the others sent (ADD_VALUES; the caller assembles `out`).
  bool Residual(::Vec out) {
    const bool finite = equations->residual(full, &local_f);
    UpdateDisplacement();
    own->InternalForce(displacement, &element_force);
    const double force = step->scales.force;
    PetscScalar* a = nullptr;
    Try(VecGetArrayWrite(out, &a), "VecGetArrayWrite");
    for (PetscInt i = first; i < last; ++i) {
      a[i - first] = evaluates_own_row[static_cast<std::size_t>(i - first)] ? local_f[i] : 0.0;
    }
    for (PetscInt i : element_local_rows) a[i - first] += element_force[i] / force;
    Try(VecRestoreArrayWrite(out, &a), "VecRestoreArrayWrite");
    const std::size_t evaluated = evaluated_remote_rows.size();
    for (std::size_t k = 0; k < evaluated; ++k) remote_values[k] = local_f[remote_rows[k]];
    for (std::size_t k = evaluated; k < remote_rows.size(); ++k) {
      remote_values[k] = element_force[remote_rows[k]] / force;
    }
    Try(VecSetValues(out, static_cast<PetscInt>(remote_rows.size()), remote_rows.data(),
                     remote_values.data(), ADD_VALUES),
        "VecSetValues");
    return finite;
  }

  void EvaluateJacobianParts() {
    equations->jacobian(full, &local_jacobian);
    UpdateDisplacement();
  }

  bool Evaluates(PetscInt row) const {
    if (row >= first && row < last) return evaluates_own_row[static_cast<std::size_t>(row - first)];
    return std::binary_search(evaluated_remote_rows.begin(), evaluated_remote_rows.end(), row);
  }

  // Whether the local Jacobian's pattern is the one the COO lists were made from.
  bool SameLocalPattern() const {
    const SpMat& m = local_jacobian;
    return !local_pattern_outer.empty() &&
           static_cast<std::size_t>(m.outerSize()) + 1 == local_pattern_outer.size() &&
           static_cast<std::size_t>(m.nonZeros()) == local_pattern_inner.size() &&
           std::equal(local_pattern_outer.begin(), local_pattern_outer.end(), m.outerIndexPtr()) &&
           std::equal(local_pattern_inner.begin(), local_pattern_inner.end(), m.innerIndexPtr());
  }

  // The COO lists of the Jacobian (see `coo_values`) for the current local Jacobian, and a new
  // matrix preallocated with them (collective; a matrix takes one COO preallocation only).
  void MakePattern() {
    const SpMat& m = local_jacobian;
    earlier_entries.insert(earlier_entries.end(), kept_entries.begin(), kept_entries.end());
    std::sort(earlier_entries.begin(), earlier_entries.end());
    earlier_entries.erase(std::unique(earlier_entries.begin(), earlier_entries.end()),
                          earlier_entries.end());
    local_pattern_outer.assign(m.outerIndexPtr(), m.outerIndexPtr() + m.outerSize() + 1);
    local_pattern_inner.assign(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
    kept_jacobian_positions.clear();
    kept_entries.clear();
    for (int j = 0; j < m.outerSize(); ++j) {
      for (int k = m.outerIndexPtr()[j]; k < m.outerIndexPtr()[j + 1]; ++k) {
        const PetscInt row = m.innerIndexPtr()[k];
        if (!Evaluates(row)) continue;
        kept_jacobian_positions.push_back(k);
        kept_entries.emplace_back(row, j);
      }
    }
    std::vector<PetscInt> rows, columns;
    auto add = [&](PetscInt i, PetscInt j) {
      rows.push_back(i);
      columns.push_back(j);
    };
    for (const auto& [i, j] : kept_entries) add(i, j);
    const SpMat& k = element_pattern.pattern();
    for (int j = 0; j < k.outerSize(); ++j) {
      for (int e = k.outerIndexPtr()[j]; e < k.outerIndexPtr()[j + 1]; ++e) {
        add(k.innerIndexPtr()[e], j);
      }
    }
    for (PetscInt i = first; i < last; ++i) add(i, i);
    for (const auto& [i, j] : earlier_entries) add(i, j);
    coo_values.assign(rows.size(), 0.0);
    MatDestroy(&jacobian);
    Try(MatCreate(PETSC_COMM_WORLD, &jacobian), "MatCreate");
    Try(MatSetSizes(jacobian, last - first, last - first, size, size), "MatSetSizes");
    Try(MatSetType(jacobian, MATMPIAIJ), "MatSetType");
    Try(MatSetPreallocationCOO(jacobian, static_cast<PetscCount>(rows.size()), rows.data(),
                               columns.data()),
        "MatSetPreallocationCOO");
  }

  // The values of the COO lists: the local Jacobian's kept entries and the elements' stiffness
  // / R (the rest stays zero).
  void FillValues() {
    const double* local = local_jacobian.valuePtr();
    const std::size_t kept = kept_jacobian_positions.size();
    for (std::size_t k = 0; k < kept; ++k) coo_values[k] = local[kept_jacobian_positions[k]];
    double* element = coo_values.data() + kept;
    const auto entries = static_cast<std::size_t>(element_pattern.pattern().nonZeros());
    std::fill_n(element, entries, 0.0);
    own->AddStiffness(displacement, 1.0 / step->scales.force, element_pattern.slots().data(),
                      element);
  }
};

namespace {

using Objects = DistributedSteps::Objects;

// Runs `body` on every process and agrees on the outcome: false on every process when it threw
// on any (the exception is kept where it was thrown, for Solve to rethrow).
template <typename Body>
bool Agreed(Objects* o, Body&& body) {
  return !AnyProcess(!Captured(&o->error, body));
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
        if (!o->SameLocalPattern()) {
          throw std::logic_error("the local Jacobian's pattern changed within a solve");
        }
        o->FillValues();
      })) {
    return PETSC_ERR_USER;
  }
  ++o->jacobian_evals;
  return MatSetValuesCOO(o->jacobian, o->coo_values.data(), INSERT_VALUES);
}

// History: merit 1/2 fnorm^2 of SNES's norm, residual_inf ||F||_inf, comp_res of the gathered
// iterate, step_length the line search's lambda.
PetscErrorCode RecordIteration(SNES snes, PetscInt iteration, PetscReal fnorm, void* context) {
  auto* o = static_cast<Objects*>(context);
  ::Vec x = nullptr, f = nullptr;
  PetscReal inf = 0.0;
  PetscErrorCode code = SNESGetSolution(snes, &x);
  if (code == 0) code = SNESGetFunction(snes, &f, nullptr, nullptr);
  if (code == 0) code = VecNorm(f, NORM_INFINITY, &inf);
  if (code != 0) return code;
  IterationRecord record = SnesIterationRecord(snes, iteration, fnorm);
  record.residual_inf = inf;
  if (!Agreed(o, [&] {
        o->Gather(x);
        record.comp_res = ComplementarityResidual(o->equations->layout, o->full);
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
  *reason = SnesTestReason({fnorm, o->vi ? fnorm < atol : inf <= o->residual_tol,
                            iteration >= max_its, max_funcs >= 0 && funcs >= max_funcs, false});
  if (*reason != SNES_CONVERGED_ITERATING) return 0;
  // Any divergence stops SNESSolve; the watch says why.
  if (o->watch.Stop(AnyProcess)) *reason = SNES_DIVERGED_FUNCTION_COUNT;
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

DistributedSteps::DistributedSteps(const std::string& defaults, const std::string& user_options,
                                   ElementSplit* element_split)
    : options_(user_options.empty() ? defaults : defaults + " " + user_options),
      user_options_(user_options),
      objects_(std::make_unique<Objects>()) {
  objects_->element_split = element_split;
  StartPetsc();
  if (Distributed()) RequireParallelLibraries();
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
  SNESType type = nullptr;
  PetscBool named = PETSC_FALSE;
  Try(SNESGetType(o->snes, &type), "SNESGetType");
  Try(PetscOptionsHasName(nullptr, prefix.c_str(), "-snes_linesearch_type", &named),
      "PetscOptionsHasName");
  if (std::string(type) == SNESNEWTONLS && !named) {
    o->line_search = std::make_unique<DistLineSearch>();
    Try(o->line_search->Install(o->snes), "SNESLineSearchShellSetUserFunc");
  }
  Try(SNESMonitorSet(o->snes, RecordIteration, o, nullptr), "SNESMonitorSet");
  Try(SNESSetConvergenceTest(o->snes, ConvergenceTest, o, nullptr), "SNESSetConvergenceTest");
}

DistributedSteps::~DistributedSteps() {
  if (!PetscRunning()) return;  // PETSc finalised first (at exit): nothing left to free
  objects_->DestroyOperands();
  SNESDestroy(&objects_->snes);
}

const StepProblem& DistributedSteps::ContactOnlyStep(const StepProblem& step, int size) {
  std::string why;
  if (!CanDistribute(step, &why)) throw std::invalid_argument(why);
  PetscErrorCapture capture;
  Objects& o = *objects_;
  if (o.model != step.model || o.size != size) o.Make(step, size);
  o.contact_only_step = step;
  o.contact_only_step.model = o.contact_only.get();
  return o.contact_only_step;
}

void DistributedSteps::Solve(const StepProblem& step, const StepRows& equations,
                             const SolverOptions& solver, const SolveControls& controls, Vec* x,
                             StepResult* result) {
  PetscErrorCapture capture;
  Objects& o = *objects_;
  const int n = equations.layout.size();
  if (o.model != step.model || o.size != n) {
    throw std::logic_error("DistributedSteps::Solve: ContactOnlyStep(step, " + std::to_string(n) +
                           ") was not called first");
  }
  o.vi = equations.bounded();
  if (o.split_pending) {
    if (!o.vi) o.SplitWhereAsked(dynamic_cast<const BodyContactModel&>(*step.model));
    o.split_pending = false;
  }
  o.step = &step;
  o.equations = &equations;
  o.result = result;
  o.watch.Start(&controls);
  o.residual_tol = solver.residual_tol;
  if (o.line_search) o.line_search->Start(solver);
  o.jacobian_evals = 0;
  o.error = nullptr;
  o.Scatter(*x, o.x);
  // The local Jacobian's pattern at the start, and a matrix for it when it is new: the pattern
  // is that of the model, the constraint and the layout, so it holds through the solve.
  o.full = *x;
  bool changed = false;
  if (!Agreed(&o, [&] {
        o.EvaluateJacobianParts();
        changed = !o.SameLocalPattern();
      })) {
    RethrowFailure(&o);
  }
  if ((o.jacobian == nullptr || AnyProcess(changed)) && !Agreed(&o, [&] { o.MakePattern(); })) {
    RethrowFailure(&o);
  }
  Try(SNESSetFunction(o.snes, o.f, EvaluateResidual, &o), "SNESSetFunction");
  Try(SNESSetJacobian(o.snes, o.jacobian, o.jacobian, EvaluateJacobian, &o), "SNESSetJacobian");
  if (o.vi) {
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
    o.Scatter(marked(equations.lower), o.lower);
    o.Scatter(marked(equations.upper), o.upper);
    Try(SNESVISetVariableBounds(o.snes, o.lower, o.upper), "SNESVISetVariableBounds");
  }
  const PetscErrorCode code = SNESSolve(o.snes, nullptr, o.x);
  if (AnyProcess(static_cast<bool>(o.error))) RethrowFailure(&o);
  o.Gather(o.x);
  *x = o.full;

  RecordSnesOutcome(o.snes, o.jacobian_evals, options_, "PETSc SNES", o.watch.stop(), result);
  result->details["processes"] = std::to_string(ProcessCount());
  if (code != 0) {
    const char* text = nullptr;
    PetscErrorMessage(code, &text, nullptr);
    result->status = Status::kFailed;
    result->message = std::string("PETSc SNESSolve failed: ") + (text != nullptr ? text : "");
    o.DestroyOperands();
  }
  RefuseUnusedOptions(code);
}

// PETSc reads most options when it sets the objects up in the first solve that iterates (a
// factorisation's when it first factors); an option still unread then never acts. Every
// process takes part in the agreement and every process throws, so that no process is left
// in a collective the others have left (issue 30).
void DistributedSteps::RefuseUnusedOptions(int code) {
  if (options_checked_ || user_options_.empty()) return;
  PetscInt iterations = 0;
  const bool iterated =
      code == 0 && SNESGetIterationNumber(objects_->snes, &iterations) == 0 && iterations > 0;
  if (!AnyProcess(iterated)) return;
  options_checked_ = true;
  const std::string prefix = OptionsPrefixFor("cbd", options_);
  const bool unused = !UnusedPetscOptions(prefix, user_options_).empty();
  if (!AnyProcess(unused)) return;
  RefuseUnusedPetscOptions(prefix, user_options_);
  throw std::invalid_argument("--petsc-options: another process found options PETSc did not use");
}

}  // namespace cb
