// One step of a problem's path as data, for the Python module's `step` (docs/your-own-method.md):
// the path is traced by run's formulation (implicit-fb unless --formulation says otherwise)
// and step k is given as a comparison's replay gives it to every formulation (path/replay.h):
// the traced state after step k - 1, the traced step's own constraint, and the prediction the
// traced step itself was given as the warm start.
#pragma once

#include <memory>
#include <string>

#include "formulations/external/step_system.h"
#include "harness/options.h"
#include "path/replay.h"
#include "problems/problem.h"

namespace cb::harness {

struct PathStep {
  Problem problem;  // owns the model the step points to
  int index = 0;    // k, 1-based
  StepProblem step;
  StartPoint warm, cold;
  StepPoint traced;  // the traced path's own answer (verified to `tolerance`)
  double tolerance = 0.0;
  std::unique_ptr<ExternalStepSystem> system;  // on `step`
};

// Step k (1-based) of the path `run` would trace with these arguments. Throws UsageError for a
// k beyond the steps the path took (with how many it took and why it stopped).
std::unique_ptr<PathStep> StepOfPath(const RunArguments& a, int k);

}  // namespace cb::harness
