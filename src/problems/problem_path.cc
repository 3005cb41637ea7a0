#include "problems/problem_path.h"

namespace cb {

PathOptions DefaultPathOptions(const Problem& problem) {
  PathOptions options;
  options.arc_length = problem.arc_length;
  options.max_steps = problem.steps;
  options.bifurcations = kDefaultBifurcationMode;
  return options;
}

StepProblem FirstStep(const Problem& problem, const PathOptions& options) {
  const StepConstraint constraint =
      problem.loading == LoadingKind::kFixedLoad
          ? StepConstraint::FixedLoad(problem.load)
          : StepConstraint::ArcLength(options.arc_length, options.lambda_weight);
  return {problem.model.get(), ZeroState(*problem.model), constraint, problem.scales};
}

PathSummary TraceProblem(const Problem& problem, Formulation& formulation,
                         const PathOptions& options, PathObserver* observer, const State* guess) {
  const State initial = ZeroState(*problem.model);
  if (problem.loading == LoadingKind::kFixedLoad) {
    return SolveFixedLoad(*problem.model, problem.scales, initial, problem.load, formulation,
                          options, observer, guess);
  }
  return TraceArcLengthPath(*problem.model, problem.scales, initial, formulation, options,
                            observer);
}

}  // namespace cb
