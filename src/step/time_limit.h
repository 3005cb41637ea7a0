// The one time-limit check of every backend (SolveControls::time_limit_s).
#pragma once

#include "core/timer.h"
#include "step/formulation.h"

namespace cb {

// Whether a solve timed by `clock` (started when the solve started) has run past
// controls.time_limit_s (never when that is 0). The backends poll it between iterations, so a
// solve stops at the first iteration that ends past the limit, and then report
// TimeLimitMessage (step/formulation.h).
inline bool PastTimeLimit(const SolveControls& controls, const Stopwatch& clock) {
  return controls.time_limit_s > 0.0 && clock.Seconds() > controls.time_limit_s;
}

}  // namespace cb
