#include "harness/path_step.h"

#include <algorithm>
#include <utility>

#include "formulations/registry.h"
#include "harness/cli.h"
#include "harness/commands.h"
#include "path/path_recorder.h"
#include "problems/problem_path.h"

namespace cb::harness {

std::unique_ptr<PathStep> StepOfPath(const RunArguments& a, int k) {
  if (k < 1) throw UsageError("step: the index is 1-based, not " + std::to_string(k));
  auto out = std::make_unique<PathStep>();
  out->problem = LoadProblem(a);
  const Problem& problem = out->problem;
  std::unique_ptr<Formulation> formulation;
  try {
    formulation = MakeFormulation(a.formulation, ConfigFor(a, a.formulation));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--formulation: ") + e.what());
  }
  PathOptions options = MakePathOptions(a, problem);
  options.start = StartKind::kWarm;  // as a comparison's reference path
  options.max_steps = std::min(options.max_steps, k);
  PathRecorder path;
  const PathSummary summary = TraceProblem(problem, *formulation, options, &path);
  const int taken = static_cast<int>(path.steps.size());
  if (k > taken) {
    throw UsageError("step " + std::to_string(k) + ": the path of '" + problem.name + "' with " +
                     formulation->name() + " took " + std::to_string(taken) + " steps (" +
                     summary.message + ")");
  }
  out->index = k;
  out->tolerance = options.tolerance;
  out->step = ReplayedStep(*problem.model, problem.scales, ZeroState(*problem.model), path, k,
                           options.lambda_weight);
  out->warm = ReplayedStart(out->step, path, k, StartKind::kWarm);
  out->cold = ReplayedStart(out->step, path, k, StartKind::kCold);
  out->traced = path.steps[static_cast<std::size_t>(k) - 1].increment;
  out->system = std::make_unique<ExternalStepSystem>(out->step);
  return out;
}

}  // namespace cb::harness
