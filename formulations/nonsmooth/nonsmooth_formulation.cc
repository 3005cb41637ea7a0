#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "formulations/nonsmooth/nonsmooth.h"
#include "formulations/nonsmooth/nonsmooth_restart.h"

namespace cb {

std::string NonsmoothName(ComplementarityFunction function) {
  return function == ComplementarityFunction::kMin ? "active-set" : "nonsmooth-fb";
}

bool NonsmoothOptions::IsValid(std::string* why) const {
  if (function != ComplementarityFunction::kFischerBurmeister &&
      function != ComplementarityFunction::kMin) {
    *why = "function must be Fischer-Burmeister or min";
    return false;
  }
  if (!(restart_residual >= 0.0)) {
    *why = "restart_residual must be >= 0";
    return false;
  }
  return solver_options.IsValid(why);
}

// --- the formulation -------------------------------------------------------------------------

namespace {

NonsmoothOptions Validated(NonsmoothOptions options) {
  std::string why;
  if (!options.IsValid(&why)) {
    throw std::invalid_argument(NonsmoothName(options.function) + " options: " + why);
  }
  return options;
}

}  // namespace

NonsmoothFormulation::NonsmoothFormulation(NonsmoothOptions options)
    : options_(Validated(std::move(options))),
      solvers_(options_.solver, options_.solver_options),
      cache_(StepEquationSystem::MakePatternCache()) {}

NonsmoothFormulation::~NonsmoothFormulation() = default;

std::string NonsmoothFormulation::name() const { return NonsmoothName(options_.function); }

std::string NonsmoothFormulation::settings() const {
  std::ostringstream out;
  out << "solver=" << options_.solver
      << ";function=" << (options_.function == ComplementarityFunction::kMin ? "min" : "fb")
      << ";linear_solver=" << options_.solver_options.linear_solver;
  return out.str();
}

namespace {

// Active sets A = {p : g^_p <= -r^_p} met along the iteration: a set seen before, but not at
// the previous iterate, is a revisit (the cycling PDAS can show without a safeguard).
class ActiveSetTrack {
 public:
  ActiveSetTrack(const StepEquationLayout& l, const Vec& x0) : l_(l), seen_{Of(x0)} {}

  // A start (the restart's): its set joins the sets seen, without counting as a change.
  void Restart(const Vec& x) { seen_.push_back(Of(x)); }
  // An iterate of the solver.
  void Observe(const Vec& y) {
    std::vector<bool> a = Of(y);
    if (a == seen_.back()) return;
    ++changes_;
    for (const auto& s : seen_) {
      if (s == a) {
        ++revisits_;
        break;
      }
    }
    seen_.push_back(std::move(a));
  }
  int size() const {
    int active = 0;
    for (bool in : seen_.back()) active += in ? 1 : 0;
    return active;
  }
  int changes() const { return changes_; }
  int revisits() const { return revisits_; }

 private:
  std::vector<bool> Of(const Vec& y) const {
    std::vector<bool> a(l_.nc);
    for (int p = 0; p < l_.nc; ++p) a[p] = y[l_.g() + p] <= -y[l_.r() + p];
    return a;
  }

  const StepEquationLayout& l_;
  std::vector<std::vector<bool>> seen_;
  int changes_ = 0;
  int revisits_ = 0;
};

// The second run from the restart's start (nonsmooth_restart.h), with the counts of both runs
// and both messages in `result`.
SolverSummary RunRestart(const StepProblem& step, const StartPoint& start,
                         const SolveControls& controls, EquationSolver& solver,
                         NonsmoothSystem& system, ActiveSetTrack* track, Vec* x,
                         StepResult* result) {
  const StepEquationLayout& l = system.layout();
  const StartPoint again = RestartPoint(step, start, l.nc);
  *x = MakeStepEquationStart(step, again, l.size());
  LeanOnClosedPairs(step, again, l, x);
  const SolveCounts first = result->counts;
  const std::string first_message = result->message;
  track->Restart(*x);
  SolverSummary summary = RunStepEquationSolver(solver, system, x, controls, result,
                                                [track](const Vec& y) { track->Observe(y); });
  result->counts.iterations += first.iterations;
  result->counts.residual_evals += first.residual_evals;
  result->counts.jacobian_evals += first.jacobian_evals;
  result->counts.linear_solves += first.linear_solves;
  result->message = "restarted after: " + first_message + "; then: " + result->message;
  return summary;
}

}  // namespace

void NonsmoothFormulation::DoSolve(const StepProblem& step, const StartPoint& start,
                                   const SolveControls& controls, StepResult* result) {
  NonsmoothSystem system(step, options_.function, cache_);
  const StepEquationLayout& l = system.layout();
  Vec x = MakeStepEquationStart(step, start, l.size());
  ActiveSetTrack track(l, x);
  SolverSummary summary = RunStepEquationSolver(solvers_.For(start), system, &x, controls, result,
                                                [&track](const Vec& y) { track.Observe(y); });
  const bool restart = TakesRestart(options_, summary, step, start);
  result->details["restarted"] = std::to_string(restart ? 1 : 0);
  if (restart) {
    summary = RunRestart(step, start, controls, solvers_.For(start), system, &track, &x, result);
  }
  result->details["active_set_size"] = std::to_string(track.size());
  result->details["active_set_changes"] = std::to_string(track.changes());
  result->details["active_set_revisits"] = std::to_string(track.revisits());
  result->details["nonsmooth_elements"] = std::to_string(system.nonsmooth_elements());
  if (summary.status != Status::kConverged && track.revisits() > 0) {
    result->message += "; the active set revisited an earlier set " +
                       std::to_string(track.revisits()) + " time(s) (cycling)";
  }
}

// --- registry factories ------------------------------------------------------------------------

std::unique_ptr<Formulation> MakeNonsmooth(ComplementarityFunction function,
                                           const FormulationConfig& config) {
  OptionReader reader(NonsmoothName(function), config.options);
  NonsmoothOptions options;
  options.restart = reader.GetBool("restart", options.restart);
  options.restart_residual = reader.GetReal("restart_residual", options.restart_residual);
  reader.Finish();
  options.function = function;
  options.solver = config.solver;
  options.solver_options = config.solver_options;
  return std::make_unique<NonsmoothFormulation>(options);
}

}  // namespace cb
