#include "path/step_solve.h"

#include <utility>

#include "path/stability.h"

namespace cb {

JudgedStep SolveAndJudge(Formulation& formulation, const StepProblem& problem,
                         const StartPoint& start, const PathOptions& options) {
  JudgedStep judged;
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
