// The state an arc-length step leaves from, with what the critical-point tests compare the
// step with.
#pragma once

#include <optional>

#include "step/step_problem.h"

namespace cb {

struct StepOrigin {
  // The step on the same branch that reached the origin.
  struct PreviousStep {
    double dlambda = 0.0;       // its load increment: a change of sign is a limit point
    int kinks = 0;              // kinks located within it
    std::optional<State> kink;  // of those, the one nearest the origin
  };

  State state;
  // Unstable modes at `state` (stability.h); -1 when not counted, or not defined: at a
  // bifurcation point an eigenvalue is zero.
  int unstable_modes = -1;
  // None at the start of the path and at a bifurcation point the path leaves onto another
  // branch.
  std::optional<PreviousStep> previous;
};

}  // namespace cb
