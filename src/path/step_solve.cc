#include "path/step_solve.h"

#include <utility>

#include "path/stability.h"

namespace cb {

JudgedStep SolveAndJudge(Formulation& formulation, const StepProblem& problem,
                         const StartPoint& start, const PathOptions& options) {
  JudgedStep judged;
  if (options.controls.interrupted && options.controls.interrupted()) {
    // Asked to stop before the solve: do not start one (its setup, the first factorisation of
    // a large model, can take seconds before the backend polls the hook).
    judged.result.status = Status::kStoppedByCaller;
    judged.result.message = "stopped by the caller before the solve";
    judged.result.point.du = Vec::Zero(problem.model->num_dofs());
    judged.result.point.g = GapsAt(*problem.model, problem.base.u);
    judged.result.point.r = problem.base.r;
    judged.state = problem.base;
    return judged;
  }
  judged.result = formulation.Solve(problem, start, options.controls);
  const StepPoint& point = judged.result.point;
  judged.verdict = Judge(problem, point, options.tolerance);
  const State& base = problem.base;
  judged.state = {base.u + point.du, point.r, base.lambda + point.dlambda};
  judged.n_contact = CountContacts(problem, GapsAt(*problem.model, judged.state.u), point.r);
  return judged;
}

bool SolvedAndVerified(const StepResult& result, const Verdict& verdict) {
  return verdict.verified && result.status != Status::kTimeLimit &&
         result.status != Status::kStoppedByCaller;
}

void RecordJudgedStep(JudgedStep judged, StepAttempt* attempt) {
  attempt->result = std::move(judged.result);
  attempt->verdict = judged.verdict;
  attempt->state = std::move(judged.state);
  attempt->n_contact = judged.n_contact;
}

}  // namespace cb
