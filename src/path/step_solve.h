// One solve of one step, judged: what every solve of the path driver does (a path step, a
// fixed-load step, a replayed step, a kink (53), a bisection trial at a critical point).
#pragma once

#include "path/path.h"

namespace cb {

// A step's answer with its verdict (docs/method.md section 7) and the state it reaches.
struct JudgedStep {
  StepResult result;
  Verdict verdict;
  State state;        // problem.base + the increment: (u + du, r, lambda + dlambda)
  int n_contact = 0;  // pairs in contact at `state` (CountContacts)
};

// Solves `problem` from `start` with options.controls and judges the answer to
// options.tolerance. With options.solve_repeats = N > 1 the solve is done N times from the
// same start, for the spread of its time: the first answer is the one judged and returned,
// its time_s is the median of the N times (time_min_s, time_max_s, time_samples), and a
// repetition whose answer differs from the first (status, iterations, or the point beyond
// options.tolerance, relative) is said in result.repeats_disagreement.
JudgedStep SolveAndJudge(Formulation& formulation, const StepProblem& problem,
                         const StartPoint& start, const PathOptions& options);

// A path step is taken only when its solve finished and its answer is verified: a solve stopped
// at the time limit (or by the caller) fails the step whatever point it stopped at, so the
// machine's speed never decides whether the path moves on.
bool SolvedAndVerified(const StepResult& result, const Verdict& verdict);

// Moves `judged` into the attempt's result, verdict, state and n_contact.
void RecordJudgedStep(JudgedStep judged, StepAttempt* attempt);

}  // namespace cb
