// The glue between PETSc's SNES and the suite that the serial PETSc formulations (SnesVi,
// petsc_adapter.h) and the distributed ones (DistributedSteps, petsc_dist/petsc_dist_adapter.h)
// share: a callback's exception kept for after SNESSolve, an iteration's record, the stopping tests
// in their order, and the controls (SolveControls' time limit and interrupt) checked between
// iterations. The outcome after SNESSolve is RecordSnesOutcome (petsc_adapter.h). A distributed
// solve takes every decision with `agree`, which reduces it over the processes (AnyProcess,
// parallel/processes.h), so that they all run the same iterations; a serial one with its own.
#pragma once

#include <petscsnes.h>

#include <exception>
#include <functional>

#include "core/timer.h"
#include "formulations/petsc/petsc_adapter.h"
#include "step/formulation.h"

namespace cb {

// Runs a callback's `work`; an exception is kept in *error (the first one: after it, `work` no
// longer runs) and false returned, so that the callback returns an error code, which unwinds
// SNESSolve, and the solve rethrows the exception after it.
template <typename Work>
bool Captured(std::exception_ptr* error, Work&& work) {
  if (*error) return false;
  try {
    work();
    return true;
  } catch (...) {
    *error = std::current_exception();
    return false;
  }
}

// What SNES tells of an iteration: its number, merit 1/2 fnorm^2 of SNES's norm, step_length
// the line search's lambda (0 at iteration 0); the caller adds residual_inf and comp_res.
IterationRecord SnesIterationRecord(SNES snes, PetscInt iteration, PetscReal fnorm);

// The stopping tests of an iteration, in the order they are taken: a NaN norm, the absolute
// test (`converged`), the iteration limit, the function-evaluation limit, the relative test.
struct SnesTests {
  PetscReal fnorm = 0.0;
  bool converged = false;
  bool iterations_reached = false;  // left false where SNES checks the limit itself (SNESVI)
  bool evaluations_reached = false;
  bool relative_converged = false;
};
SNESConvergedReason SnesTestReason(const SnesTests& tests);

// SolveControls between iterations: the time limit since Start and the interrupt.
class SnesControlsWatch {
 public:
  // Before each solve.
  void Start(const SolveControls* controls);
  // Whether the controls stop the solve here, each decided with `agree`; then stop() says why.
  bool Stop(const std::function<bool(bool)>& agree);
  SnesStop stop() const { return stop_; }

 private:
  const SolveControls* controls_ = nullptr;
  Stopwatch clock_;
  SnesStop stop_;
};

}  // namespace cb
