// The distributed step system and its Newton (PETSc SNES over MPI), which every dist-*
// formulation hands its step to. Built only with PETSc (petsc_dist.cmake).
//
// Unknowns and rows are those of common/step_equations.h (du, g^, r^, dlambda[, rho]) in one
// MPI vector of PETSc's default layout: contiguous row ranges, so that the scalar rows (the rho
// row (32), the step row (33)) fall to the last process. Each process evaluates
//   - its own elements' share of (29) / R, the internal force and the stiffness of the body
//     restricted to its elements (ElasticBody::Restricted, element_partition.h), and
//   - its own contact pairs (element_partition.h: those at the nodes whose lowest free dof it
//     owns) from the formulation's own serial step equations on its contact-only model
//     (own_pairs_model.h: no element, every pair in the layout, only its own evaluated, the load
//     on its own rows): it keeps the rows (30) and the complementarity rows of its pairs, their
//     share of the contact term of (29) on their nodes' dofs, its own displacement rows (the
//     load and that share), and, on the last process, the scalar rows (32), (33);
// each adds them into whatever rows they are (PETSc sends the entries of other processes' rows).
// The equations read the whole iterate, which every evaluation gathers on every process
// (VecScatterCreateToAll): the problem description and the iterate are replicated, the element
// and pair work and the matrix are not (docs/scale-out.md says what this limits).
//
// The Jacobian is MATMPIAIJ assembled through PETSc's COO interface: the entries (the kept ones
// of the local Jacobian, the elements' stiffness, the diagonal) are listed once per pattern of
// the local Jacobian (MatSetPreallocationCOO; every entry of an earlier pattern on the same model
// is kept), and each evaluation writes their values in that order (MatSetValuesCOO).
// Solves: PETSc options, under a prefix of each instance's own ("cbd<k>_"), the defaults then
// the user's string (--petsc-options):
//   equations  -snes_type newtonls -ksp_type preonly -pc_type lu
//              -pc_factor_mat_solver_type mumps -snes_max_it <the solver's max_iterations>,
//              and the serial Newton's line search (dist_line_search.h)
//   SNESVI     -snes_type vinewtonrsls | vinewtonssls, the same direct solve, -snes_atol 1e-10
//              -snes_rtol 0 -snes_max_it 200 (the defaults of petsc_adapter.h, with MUMPS,
//              the parallel factorisation Debian's PETSc has).
// The formulation's `linear=amg` replaces the direct solve by a field split; whenever the options
// choose PCFIELDSPLIT for the equations, the du rows and the rest are its splits (field_split.h).
// The stopping test of the equations is the serial solvers' ||F||_inf <= residual_tol; that of
// SNESVI its own norm below -snes_atol. Every decision (the stopping test, an interrupt, the
// time limit, a failed evaluation) is taken on values reduced over all processes, so that the
// processes run the same iterations and return the same StepResult (the verdict then judges
// the gathered answer identically everywhere). An exception in an evaluation on any process
// makes every process's evaluation fail together, and SNESSolve returns on all of them.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/sparse.h"
#include "formulations/common/step_equations.h"
#include "formulations/common/step_rows.h"
#include "parallel/element_split.h"
#include "step/formulation.h"

namespace cb {

class DistributedSteps {
 public:
  // `defaults` and then `user_options` (PETSc's syntax); throws std::invalid_argument naming
  // an option PETSc refuses. Starts PETSc (and MPI) on first use. Each partition of a body
  // is recorded in `element_split` (none: not recorded).
  DistributedSteps(const std::string& defaults, const std::string& user_options,
                   ElementSplit* element_split = nullptr);
  ~DistributedSteps();
  DistributedSteps(const DistributedSteps&) = delete;
  DistributedSteps& operator=(const DistributedSteps&) = delete;

  const std::string& options() const { return options_; }

  struct Objects;  // the PETSc objects and one solve's context (petsc_dist_adapter.cc)

  // The step on this process's contact-only model of step.model (a BodyContactModel; otherwise
  // std::invalid_argument; own_pairs_model.h), for the formulation's local equations of `size`
  // rows; valid until the next call, which Solve must follow for the same step and size.
  const StepProblem& ContactOnlyStep(const StepProblem& step, int size);

  // Solves the formulation's serial rows on the contact-only step (`equations`, see the top of
  // the file; their start and finish are the caller's) from *x (full, identical on every
  // process), leaving the last iterate in *x and filling `result` (status, message, counts,
  // history, details; not the point). With bounds, SNESVI; otherwise converged when
  // ||F||_inf <= solver.residual_tol, with the serial Newton's line search and `solver`'s
  // settings of it (dist_line_search.h) unless the options name another -snes_linesearch_type.
  void Solve(const StepProblem& step, const StepRows& equations, const SolverOptions& solver,
             const SolveControls& controls, Vec* x, StepResult* result);

 private:
  // The user's options, refused after the first solve that iterated when PETSc left any of
  // them unread (petsc_unused_options.h), as the petsc-* formulations do.
  void RefuseUnusedOptions(int code);  // SNESSolve's PetscErrorCode

  std::string options_;
  std::string user_options_;
  bool options_checked_ = false;
  std::unique_ptr<Objects> objects_;
};

// Whether a model can be distributed (a body against obstacles), with the reason if not.
bool CanDistribute(const StepProblem& step, std::string* why);

}  // namespace cb
