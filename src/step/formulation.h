// The common interface of every rendering of a loading step (docs/architecture.md, "The layers").
// Solve() is non-virtual: it validates, times and fills the common fields, then calls the
// private DoSolve (the pattern of Drake's SolverBase).
#pragma once

#include <any>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/types.h"
#include "step/step_problem.h"

namespace cb {

enum class StartKind { kWarm, kCold };
const char* ToString(StartKind kind);

// What the path driver hands a formulation as its start.
//  kWarm: `du`, `dlambda` the predicted increment (the previous step's increment scaled to this
//         step's size, or the tangent predictor on the first step), `r` the reactions of the
//         known state; `warm_state` the previous step's StepResult::warm_state, if any (the
//         one channel for what a step takes from the previous one: src/step/warm_state.md).
//  kCold: a fixed start that does not use the previous step (each formulation documents it).
// `across_contact_change`: the prediction was bent at a contact change it runs across (the
// corner prediction, src/path/corner_prediction.h); the answer lies just past a corner of the
// path, where a solver's monotone line search creeps (formulations/common/start_solvers.h).
struct StartPoint {
  StartKind kind = StartKind::kWarm;
  Vec du;
  double dlambda = 0.0;
  Vec r;
  std::any warm_state;
  bool across_contact_change = false;
};

struct SolveCounts {
  int iterations = 0;
  int residual_evals = 0;
  int jacobian_evals = 0;
  int linear_solves = 0;
};

// One row of the per-iteration history.
struct IterationRecord {
  int iteration = 0;
  double merit = 0.0;         // 1/2 ||F||^2 of the formulation's own system
  double residual_inf = 0.0;  // ||F||_inf of the formulation's own system
  double comp_res = 0.0;      // ||min(g/L, -r/R)||_inf at the iterate, where cheap (else NaN)
  double step_length = 0.0;
};

struct StepResult {
  StepPoint point;
  Status status = Status::kNotRun;  // the solver's own claim ("found")
  std::string message;
  SolveCounts counts;
  double time_s = 0.0;  // wall time of the solve alone (of repeated solves: their median)
  // The spread of time_s: one solve's time, or with PathOptions::solve_repeats > 1 the
  // fastest and slowest of the repetitions (step_solve.h), and how many were timed.
  double time_min_s = 0.0;
  double time_max_s = 0.0;
  int time_samples = 1;
  // Whether every repetition gave the first one's answer ("" when they agreed or there was
  // one solve; else what differed, e.g. "repetition 2: 7 iterations, not 6").
  std::string repeats_disagreement;
  std::vector<IterationRecord> history;
  std::map<std::string, std::string> details;  // backend specifics (raw return codes, ...)
  // What a warm start of the next step may reuse, handed back through StartPoint::warm_state;
  // a formulation keeps no such state in its members (src/step/warm_state.md).
  std::any warm_state;
};

// Limits and hooks the harness sets for every formulation alike.
struct SolveControls {
  double time_limit_s = 0.0;          // 0: none
  std::function<bool()> interrupted;  // polled between iterations; true stops the solve
};

// The reason every backend gives for a solve stopped at SolveControls::time_limit_s
// (Status::kTimeLimit), so the records say the same thing whoever ran out of time.
std::string TimeLimitMessage(double time_limit_s);

class Formulation {
 public:
  virtual ~Formulation() = default;
  virtual std::string name() const = 0;
  // The solver or backend doing the work (records' `solver` column).
  virtual std::string solver() const = 0;
  // The settings that distinguish this instance in the records (solver, eta case, ...).
  virtual std::string settings() const = 0;

  // Whether this formulation can take `step` (a well-formed one, StepProblem::Validate),
  // decided before solving from what the step asks: its constraint kind (an energy NLP cannot
  // express an arc-length step), its size (a dense backend's limit), what the model offers (an
  // energy to minimise). Otherwise false with the reason, naming the formulation, in *why
  // (when not null). Asked once per problem by the harness and the benchmarks: capability
  // depends on the model, its size and the kind of step, not on where a path is.
  bool Accepts(const StepProblem& step, std::string* why = nullptr) const;

  // Throws std::invalid_argument on a malformed step or start (sizes), or on a step that
  // Accepts refuses (with its reason).
  StepResult Solve(const StepProblem& step, const StartPoint& start,
                   const SolveControls& controls = {});

 private:
  // Accepts without the null check; the default accepts every step.
  virtual bool DoAccepts(const StepProblem& /*step*/, std::string* /*why*/) const { return true; }
  virtual void DoSolve(const StepProblem& step, const StartPoint& start,
                       const SolveControls& controls, StepResult* result) = 0;
};

}  // namespace cb
