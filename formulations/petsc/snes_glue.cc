#include "formulations/petsc/snes_glue.h"

#include <cmath>

#include "step/time_limit.h"

namespace cb {

IterationRecord SnesIterationRecord(SNES snes, PetscInt iteration, PetscReal fnorm) {
  SNESLineSearch line_search = nullptr;
  PetscReal step = 0.0;
  if (iteration > 0 && SNESGetLineSearch(snes, &line_search) == 0) {
    SNESLineSearchGetLambda(line_search, &step);
  }
  IterationRecord record;
  record.iteration = static_cast<int>(iteration);
  record.merit = 0.5 * fnorm * fnorm;
  record.step_length = step;
  return record;
}

SNESConvergedReason SnesTestReason(const SnesTests& tests) {
  if (std::isnan(tests.fnorm)) return SNES_DIVERGED_FNORM_NAN;
  if (tests.converged) return SNES_CONVERGED_FNORM_ABS;
  if (tests.iterations_reached) return SNES_DIVERGED_MAX_IT;
  if (tests.evaluations_reached) return SNES_DIVERGED_FUNCTION_COUNT;
  if (tests.relative_converged) return SNES_CONVERGED_FNORM_RELATIVE;
  return SNES_CONVERGED_ITERATING;
}

void SnesControlsWatch::Start(const SolveControls* controls) {
  controls_ = controls;
  clock_ = Stopwatch();
  stop_ = SnesStop{false, false, controls->time_limit_s};
}

bool SnesControlsWatch::Stop(const std::function<bool(bool)>& agree) {
  const SolveControls& c = *controls_;
  stop_.timed_out = agree(PastTimeLimit(c, clock_));
  stop_.stopped = stop_.timed_out || agree(c.interrupted && c.interrupted());
  return stop_.stopped;
}

}  // namespace cb
