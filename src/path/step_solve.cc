#include "path/step_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/median.h"
#include "path/stability.h"

namespace cb {

namespace {

// The largest difference between two answers, each part relative to the first answer's size
// (at least 1): the increment (du, dlambda) and the reactions r.
double AnswerDifference(const StepPoint& first, const StepPoint& other) {
  auto relative = [](const Vec& a, const Vec& b) {
    if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
    if (a.size() == 0) return 0.0;
    return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, a.lpNorm<Eigen::Infinity>());
  };
  const double dlambda =
      std::abs(first.dlambda - other.dlambda) / std::max(1.0, std::abs(first.dlambda));
  return std::max({relative(first.du, other.du), relative(first.r, other.r), dlambda});
}

// "" when repetition `k` (from 2) gave the first solve's answer: the same status, the same
// iterations and a point within `tolerance` of it (AnswerDifference); else what differed.
std::string Disagreement(const StepResult& first, const StepResult& other, int k,
                         double tolerance) {
  const std::string which = "repetition " + std::to_string(k) + ": ";
  if (other.status != first.status) {
    return which + "status " + ToString(other.status) + ", not " + ToString(first.status);
  }
  if (other.counts.iterations != first.counts.iterations) {
    return which + std::to_string(other.counts.iterations) + " iterations, not " +
           std::to_string(first.counts.iterations);
  }
  const double difference = AnswerDifference(first.point, other.point);
  if (!(difference <= tolerance)) {
    return which + "an answer " + std::to_string(difference) + " away (relative)";
  }
  return "";
}

// Solves `problem` options.solve_repeats times from the same start. The first answer is kept;
// its time becomes the median of all the solves' times with their min and max, and the first
// repetition that disagreed with it is said in repeats_disagreement. Repeating stops at a solve
// stopped by the caller or the time limit (its time is no solve's time).
StepResult RepeatedSolve(Formulation& formulation, const StepProblem& problem,
                         const StartPoint& start, const PathOptions& options) {
  StepResult first = formulation.Solve(problem, start, options.controls);
  std::vector<double> times = {first.time_s};
  const auto cut_short = [](const StepResult& r) {
    return r.status == Status::kStoppedByCaller || r.status == Status::kTimeLimit;
  };
  for (int k = 2; k <= options.solve_repeats && !cut_short(first); ++k) {
    if (options.controls.interrupted && options.controls.interrupted()) break;
    const StepResult again = formulation.Solve(problem, start, options.controls);
    if (cut_short(again)) break;
    times.push_back(again.time_s);
    if (first.repeats_disagreement.empty()) {
      first.repeats_disagreement = Disagreement(first, again, k, options.tolerance);
    }
  }
  first.time_s = Median(times);
  first.time_min_s = *std::min_element(times.begin(), times.end());
  first.time_max_s = *std::max_element(times.begin(), times.end());
  first.time_samples = static_cast<int>(times.size());
  return first;
}

}  // namespace

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
  judged.result = RepeatedSolve(formulation, problem, start, options);
  if (judged.result.status == Status::kFailed && options.controls.interrupted &&
      options.controls.interrupted()) {
    // A solve that failed because an interrupt abandoned its work (a factorisation:
    // solvers/interruptible_klu.h) was stopped by the caller, not a failed step to cut back.
    judged.result.status = Status::kStoppedByCaller;
  }
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
