// Google Benchmark timings of the implicit smoothed-FB formulation (issue 2 targets):
//  - P1 `block` cold solve for n = 25, 50, 100, 200 (the report's section 5.1 start);
//  - one warm P3 `arch-curved` step, replayed from an accepted state of the path;
//  - time per Newton iteration against one sparse factorisation + solve of the same Jacobian.
// A run whose answer fails the verdict is skipped with an error, not timed.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "core/timer.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "path/path.h"
#include "path/replay.h"
#include "problems/problem.h"
#include "solvers/linear_solver.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

constexpr double kTolerance = 1e-8;

ImplicitFbOptions Options(const std::string& solver = "newton") {
  ImplicitFbOptions o;
  o.solver = solver;
  return o;
}

// P1 from the cold start, a fresh formulation per run (its first solve includes the symbolic
// analysis, as a user's single solve does).
void BM_BlockColdSolve(benchmark::State& state) {
  const Problem p = MakeProblem("block", {{"n", std::to_string(state.range(0))}});
  PathOptions options;
  options.start = StartKind::kCold;
  int iterations = 0;
  for (auto _ : state) {
    ImplicitFb formulation(Options());
    const PathSummary s = SolveFixedLoad(*p.model, p.scales, ZeroState(*p.model), p.load,
                                         formulation, options, nullptr);
    if (s.status != Status::kConverged) {
      state.SkipWithError(("not verified: " + s.message).c_str());
      return;
    }
  }
  {
    ImplicitFb formulation(Options());
    StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load),
                     p.scales};
    StartPoint cold;
    cold.kind = StartKind::kCold;
    iterations = formulation.Solve(step, cold).counts.iterations;
  }
  state.counters["d"] = p.model->num_dofs();
  state.counters["newton_iterations"] = iterations;
}
BENCHMARK(BM_BlockColdSolve)->Arg(25)->Arg(50)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

// A warm P3 step in replay mode: the state after accepted step `k` of the reference path and
// the increment that led there; the timed work is step k + 1 with a formulation whose pattern
// is already analysed (the steady state of a path).
void BM_ArchCurvedWarmStep(benchmark::State& state) {
  const Problem p = MakeProblem("arch-curved");
  const int k = static_cast<int>(state.range(0));
  ImplicitFb reference(Options());
  PathRecorder recorder;
  PathOptions options;
  options.arc_length = p.arc_length;
  options.max_steps = k;
  TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), reference, options, &recorder);
  if (static_cast<int>(recorder.states.size()) < k) {
    state.SkipWithError("the reference path did not reach the requested step");
    return;
  }
  const State& base = recorder.states[k - 1];
  StepProblem step{p.model.get(), base, StepConstraint::ArcLength(p.arc_length), p.scales};
  StartPoint start;
  start.du = recorder.increments[k - 1].du;
  start.dlambda = recorder.increments[k - 1].dlambda;
  start.r = base.r;
  ImplicitFb formulation(Options());
  StepResult result = formulation.Solve(step, start);  // analyses the pattern
  for (auto _ : state) {
    result = formulation.Solve(step, start);
    // A pointer, not the double: GCC mis-handles DoNotOptimize(double&) (google/benchmark#903).
    benchmark::DoNotOptimize(result.point.du.data());
  }
  const Verdict v = Judge(step, result.point, kTolerance);
  if (!v.verified) {
    const std::string why = "step not verified: eq " + std::to_string(v.eq_res) + " comp " +
                            std::to_string(v.comp_res) + " step " + std::to_string(v.step_res) +
                            " (" + result.message + ")";
    state.SkipWithError(why.c_str());
    return;
  }
  state.counters["newton_iterations"] = result.counts.iterations;
}
BENCHMARK(BM_ArchCurvedWarmStep)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// The whole P3 path of the report's Table 2 (1604 steps), kinks located.
void BM_ArchCurvedPath(benchmark::State& state) {
  const Problem p = MakeProblem("arch-curved");
  PathOptions options;
  options.arc_length = p.arc_length;
  options.max_steps = p.steps;
  for (auto _ : state) {
    ImplicitFb formulation(Options());
    const PathSummary s =
        TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), formulation, options, nullptr);
    if (s.status != Status::kConverged) {
      state.SkipWithError(("path failed: " + s.message).c_str());
      return;
    }
  }
  state.counters["steps"] = p.steps;
}
BENCHMARK(BM_ArchCurvedPath)->Unit(benchmark::kMillisecond)->Iterations(3);

// Time per Newton iteration of a solve divided by the time of one factorisation + solve of the
// Jacobian at its answer (same pattern, same values, pattern analysed beforehand). The
// benchmark's own time is the factorisation + solve; the counters carry the comparison.
void IterationOverFactorization(benchmark::State& state, const StepProblem& step,
                                const StartPoint& start) {
  ImplicitFb formulation(Options());
  StepResult result = formulation.Solve(step, start);  // analysis outside the measurement
  Stopwatch clock;
  const int repeats = 200;
  for (int i = 0; i < repeats; ++i) result = formulation.Solve(step, start);
  const double per_iteration = clock.Seconds() / repeats / result.counts.iterations;
  if (!Judge(step, result.point, kTolerance).verified) {
    state.SkipWithError("step not verified");
    return;
  }
  // The Jacobian at the answer.
  ImplicitFbStart at = MakeImplicitFbStart(step, start, formulation.options());
  ImplicitFbSystem system(step, EtaEquation{formulation.options().eta, at.gamma});
  const ImplicitFbLayout& l = system.layout();
  Vec x(l.size());
  x << result.point.du, result.point.g / step.scales.length, result.point.r / step.scales.force,
      result.point.dlambda, 0.0;
  SpMat jacobian;
  system.Jacobian(x, &jacobian);
  auto linear = MakeLinearSolver(formulation.options().solver_options.linear_solver);
  Vec rhs = Vec::Ones(l.size()), solution;
  linear->Factorize(jacobian);  // analysis outside the measurement
  clock.Restart();
  for (int i = 0; i < repeats; ++i) {
    linear->Factorize(jacobian);
    linear->Solve(rhs, &solution);
  }
  const double factorize_solve = clock.Seconds() / repeats;
  // The work of one Newton iteration without the per-step overhead (start point, initial
  // residual, bookkeeping): Jacobian, factorisation, solve, one trial residual (whose value is
  // the next iteration's right-hand side).
  Vec residual, step_dx;
  system.Residual(x, &residual);
  clock.Restart();
  for (int i = 0; i < repeats; ++i) {
    system.Jacobian(x, &jacobian);
    linear->Factorize(jacobian);
    linear->Solve(residual, &step_dx);
    system.Residual(x, &residual);
  }
  const double iteration_kernel = clock.Seconds() / repeats;
  for (auto _ : state) {
    linear->Factorize(jacobian);
    linear->Solve(rhs, &solution);
    benchmark::DoNotOptimize(solution.data());
  }
  state.counters["newton_iterations"] = result.counts.iterations;
  state.counters["per_newton_iteration_us"] = per_iteration * 1e6;
  state.counters["factorize_solve_us"] = factorize_solve * 1e6;
  state.counters["ratio"] = per_iteration / factorize_solve;
  state.counters["iteration_kernel_us"] = iteration_kernel * 1e6;
  state.counters["kernel_ratio"] = iteration_kernel / factorize_solve;
}

void BM_IterationOverFactorizationBlock(benchmark::State& state) {
  const Problem p = MakeProblem("block");
  StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load),
                   p.scales};
  StartPoint cold;
  cold.kind = StartKind::kCold;
  IterationOverFactorization(state, step, cold);
}
BENCHMARK(BM_IterationOverFactorizationBlock)->Unit(benchmark::kMillisecond);

void BM_IterationOverFactorizationArchCurved(benchmark::State& state) {
  const Problem p = MakeProblem("arch-curved");
  ImplicitFb reference(Options());
  PathRecorder recorder;
  PathOptions options;
  options.arc_length = p.arc_length;
  options.max_steps = 100;
  TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), reference, options, &recorder);
  StepProblem step{p.model.get(), recorder.states.back(), StepConstraint::ArcLength(p.arc_length),
                   p.scales};
  StartPoint start;
  start.du = recorder.increments.back().du;
  start.dlambda = recorder.increments.back().dlambda;
  start.r = recorder.states.back().r;
  IterationOverFactorization(state, step, start);
}
BENCHMARK(BM_IterationOverFactorizationArchCurved)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace cb

BENCHMARK_MAIN();
