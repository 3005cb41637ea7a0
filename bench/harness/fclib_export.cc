#include "harness/fclib_export.h"

#include <stdexcept>
#include <vector>

#include "harness/commands.h"
#include "harness/interrupt.h"
#include "io/fclib_file.h"
#include "path/path.h"
#include "problems/problem_path.h"

namespace cb::harness {

namespace {

// The accepted states of a path, in order.
struct AcceptedStates final : PathObserver {
  void OnAttempt(const StepAttempt& attempt) override {
    if (attempt.accepted) states.push_back(attempt.state);
  }
  std::vector<State> states;
};

// FCLIB's global problem is a linear body with a symmetric M (fclib_writer.cc refuses the rest
// too; here before any solve).
void CheckWritable(const Problem& problem) {
  if (!problem.model->is_linear()) {
    throw InputError("--format fclib: '" + problem.name +
                     "' is not small-deformation (FCLIB problems are linear)");
  }
  if (!problem.model->has_energy()) {
    throw InputError("--format fclib: '" + problem.name +
                     "' has no energy (a non-symmetric M; FCLIB's M is symmetric)");
  }
}

void Write(const Problem& problem, const std::string& path, const io::FclibState* solution,
           const io::FclibState* guess) {
  try {
    io::WriteFclibFile(problem, path, solution, guess);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

io::FclibState FclibStateOf(const State& state) { return {state.u, state.r}; }

// The accepted states of implicit-fb's run of the problem (`steps` steps of a path).
AcceptedStates Trace(const RunArguments& a, const Problem& problem, int steps,
                     PathSummary* summary) {
  PathOptions options = DefaultPathOptions(problem);
  options.max_steps = steps;
  options.controls.interrupted = [] { return InterruptRequested(); };
  const auto formulation = MakeConfiguredFormulation(a, "implicit-fb");
  AcceptedStates accepted;
  *summary = TraceProblem(problem, *formulation, options, &accepted);
  if (summary->status == Status::kStoppedByCaller) {
    AcknowledgeInterrupt();
    throw Interrupted("interrupted while solving the problem to export");
  }
  return accepted;
}

std::string ExportFixedLoad(const RunArguments& a, const Problem& problem) {
  PathSummary summary;
  const AcceptedStates accepted = Trace(a, problem, 1, &summary);
  if (accepted.states.empty()) {
    Write(problem, a.out, nullptr, nullptr);
    return "without /solution: implicit-fb's solve was not verified (" + summary.message + ")";
  }
  const io::FclibState solution = FclibStateOf(accepted.states.back());
  Write(problem, a.out, &solution, nullptr);
  return "with implicit-fb's verified answer as /solution";
}

std::string ExportPathStep(const RunArguments& a, const Problem& problem, int step) {
  PathSummary summary;
  const AcceptedStates accepted = Trace(a, problem, step, &summary);
  if (static_cast<int>(accepted.states.size()) < step) {
    throw std::runtime_error("--step " + std::to_string(step) + ": implicit-fb's path of '" +
                             problem.name + "' stopped after " +
                             std::to_string(accepted.states.size()) + " steps (" + summary.message +
                             ")");
  }
  const State& answer = accepted.states[static_cast<std::size_t>(step) - 1];
  const State previous =
      step > 1 ? accepted.states[static_cast<std::size_t>(step) - 2] : ZeroState(*problem.model);
  Problem at_step = problem;  // the step as a fixed-load problem at its load
  at_step.loading = LoadingKind::kFixedLoad;
  at_step.load = answer.lambda;
  const io::FclibState solution = FclibStateOf(answer);
  const io::FclibState guess = FclibStateOf(previous);
  Write(at_step, a.out, &solution, &guess);
  return "step " + std::to_string(step) + " at lambda = " + std::to_string(answer.lambda) +
         ", its answer as /solution and step " + std::to_string(step - 1) +
         "'s state as /guesses/1";
}

}  // namespace

std::string ExportFclib(const RunArguments& a, const Problem& problem) {
  CheckWritable(problem);
  if (a.export_step && problem.loading == LoadingKind::kFixedLoad) {
    throw UsageError("--step: '" + problem.name + "' is a fixed-load problem (one solve)");
  }
  if (a.export_step) return ExportPathStep(a, problem, *a.export_step);
  if (problem.loading != LoadingKind::kFixedLoad) {
    Write(problem, a.out, nullptr, nullptr);
    return "at its load, without /solution (a path: --step N writes its step N with the answer)";
  }
  return ExportFixedLoad(a, problem);
}

}  // namespace cb::harness
