// Google Benchmark timings of the implicit smoothed-FB formulation against its targets
// (docs/findings.md, "Performance"), each for the linear solvers named in the benchmark's name
// (`cholmod`, the default condensed Cholesky, and `klu`, the full-system LU):
//  - P1 `block` cold solve for n = 25 ... 400 (the report's section 5.1 start), with the peak
//    resident memory of one solve (VmHWM after resetting the high-water mark);
//  - one warm P3 `arch-curved` step, replayed from an accepted state of the path;
//  - the whole P2 `arch-flat` and P3 paths, with the median Newton iterations per step;
//  - time per Newton iteration against one sparse LU factorisation + solve of the same
//    Jacobian (KLU refactorisation with the previous pivot order, the strictest comparator).
// A run whose answer fails the verdict is skipped with an error, not timed.
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench_support.h"
#include "core/blas_info.h"
#include "core/timer.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "path/path.h"
#include "path/replay.h"
#include "problems/problem.h"
#include "solvers/condensed_cholesky.h"
#include "solvers/linear_solver.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

constexpr double kTolerance = 1e-8;

ImplicitFbOptions Options(const std::string& linear_solver) {
  ImplicitFbOptions o;
  o.solver = "newton";
  o.solver_options.linear_solver = linear_solver;
  return o;
}

// Peak resident memory of the process (Linux): writing 5 to clear_refs resets VmHWM to the
// current resident size, so VmHWM after a solve is that solve's peak.
bool ResetPeakMemory() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  return static_cast<bool>(out);
}
double StatusFieldMb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field + ":", 0) == 0) {
      std::istringstream fields(line.substr(field.size() + 1));
      double kb = 0.0;
      fields >> kb;
      return kb / 1024.0;
    }
  }
  return -1.0;
}

// The calling thread's CPU time in seconds.
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Newton iterations of the accepted arc-length steps of a path.
class IterationCounter final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& attempt) override {
    if (attempt.accepted) iterations.push_back(attempt.result.counts.iterations);
  }
  double Median() const {
    if (iterations.empty()) return 0.0;
    std::vector<int> v = iterations;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  }
  std::vector<int> iterations;
};

// P1 from the cold start, a fresh formulation per run (its first solve includes the symbolic
// analysis, as a user's single solve does).
void BlockColdSolve(benchmark::State& state, const std::string& linear_solver) {
  const Problem p = MakeProblem("block", {{"n", std::to_string(state.range(0))}});
  PathOptions options;
  options.start = StartKind::kCold;
  for (auto _ : state) {
    ImplicitFb formulation(Options(linear_solver));
    const PathSummary s = SolveFixedLoad(*p.model, p.scales, ZeroState(*p.model), p.load,
                                         formulation, options, nullptr);
    if (s.status != Status::kConverged) {
      state.SkipWithError(("not verified: " + s.message).c_str());
      return;
    }
  }
  // One more solve, untimed, for the iteration count and the peak memory. The memory the timed
  // solves freed goes back to the system first, so that the solve's own peak shows.
  malloc_trim(0);
  const double rss_before = StatusFieldMb("VmRSS");
  const bool reset = ResetPeakMemory();
  int iterations = 0;
  {
    ImplicitFb formulation(Options(linear_solver));
    StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load),
                     p.scales};
    StartPoint cold;
    cold.kind = StartKind::kCold;
    iterations = formulation.Solve(step, cold).counts.iterations;
  }
  const double peak = StatusFieldMb("VmHWM");
  state.counters["d"] = p.model->num_dofs();
  state.counters["newton_iterations"] = iterations;
  if (reset && peak > 0.0) {
    state.counters["peak_rss_mb"] = peak;
    // The solve's own memory: peak minus what the process held before it (the problem).
    state.counters["solve_peak_mb"] = peak - rss_before;
    state.counters["solve_bytes_per_dof"] = (peak - rss_before) * 1048576.0 / p.model->num_dofs();
  }
}

// A warm P3 step in replay mode: the state after accepted step `k` of the reference path and
// the increment that led there; the timed work is step k + 1 with a formulation whose pattern
// is already analysed (the steady state of a path).
void ArchCurvedWarmStep(benchmark::State& state, const std::string& linear_solver) {
  const Problem p = MakeProblem("arch-curved");
  const int k = static_cast<int>(state.range(0));
  ImplicitFb reference(Options("klu"));
  PathRecorder recorder;
  PathOptions options;
  options.arc_length = p.arc_length;
  options.max_steps = k;
  TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), reference, options, &recorder);
  if (static_cast<int>(recorder.steps.size()) < k) {
    state.SkipWithError("the reference path did not reach the requested step");
    return;
  }
  const State& base = recorder.steps[k - 1].state;
  StepProblem step{p.model.get(), base, StepConstraint::ArcLength(p.arc_length), p.scales};
  StartPoint start;
  start.du = recorder.steps[k - 1].increment.du;
  start.dlambda = recorder.steps[k - 1].increment.dlambda;
  start.r = base.r;
  ImplicitFb formulation(Options(linear_solver));
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

// A whole arc-length path (P3: the report's Table 2, 1604 steps; P2: its default steps), kinks
// located, with the median Newton iterations of the accepted steps.
void ArchPath(benchmark::State& state, const std::string& problem,
              const std::string& linear_solver) {
  const Problem p = MakeProblem(problem);
  PathOptions options;
  options.arc_length = p.arc_length;
  options.max_steps = p.steps;
  IterationCounter counter;
  for (auto _ : state) {
    ImplicitFb formulation(Options(linear_solver));
    counter.iterations.clear();
    const PathSummary s =
        TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), formulation, options, &counter);
    if (s.status != Status::kConverged) {
      state.SkipWithError(("path failed: " + s.message).c_str());
      return;
    }
  }
  state.counters["steps"] = p.steps;
  state.counters["median_iterations"] = counter.Median();
}

// Time per Newton iteration of a solve (with `linear_solver`) divided by the time of one LU
// factorisation + solve of the Jacobian at its answer (KLU, pattern analysed beforehand,
// refactorisation with the previous pivot order). The benchmark's own time is that
// factorisation + solve; the counters carry the comparison:
//  - ratio: whole solves (start, bookkeeping included) / iterations / LU;
//  - kernel_ratio: one iteration's work alone (factorisation, solve, and the residual at the new
//    point with its Jacobian for the next iteration, from one pass as Newton evaluates them at an
//    accepted full step);
//  - ratio_cpu, kernel_ratio_cpu: the same from the thread's CPU time, which the load of a shared
//    machine does not inflate the way it does wall time (the P3 case is single-threaded: KLU
//    and the evaluations; where CHOLMOD calls a threaded BLAS they leave its threads out).
void IterationOverFactorization(benchmark::State& state, const StepProblem& step,
                                const StartPoint& start, const std::string& linear_solver) {
  ImplicitFb formulation(Options(linear_solver));
  StepResult result = formulation.Solve(step, start);  // analysis outside the measurement
  // Repeat for at least 0.5 s (and 3 solves); the wall time of one repetition, and its thread
  // CPU time into *cpu when given.
  auto repeat_for = [](auto&& work, double* cpu = nullptr) {
    Stopwatch clock;
    const double cpu_start = ThreadCpuSeconds();
    int repeats = 0;
    do {
      work();
      ++repeats;
    } while (repeats < 3 || clock.Seconds() < 0.5);
    if (cpu != nullptr) *cpu = (ThreadCpuSeconds() - cpu_start) / repeats;
    return clock.Seconds() / repeats;
  };
  double per_solve_cpu = 0.0;
  const double per_solve =
      repeat_for([&] { result = formulation.Solve(step, start); }, &per_solve_cpu);
  const double per_iteration = per_solve / result.counts.iterations;
  if (!Judge(step, result.point, kTolerance).verified) {
    state.SkipWithError("step not verified");
    return;
  }
  // The Jacobian at the answer.
  ImplicitFbStart at = MakeImplicitFbStart(step, start, formulation.options());
  ImplicitFbSystem system(step, EtaEquation{formulation.options().eta, at.gamma});
  const StepEquationLayout& l = system.layout();
  Vec x(l.size());
  x << result.point.du, result.point.g / step.scales.length, result.point.r / step.scales.force,
      result.point.dlambda, 0.0;
  SpMat jacobian;
  system.Jacobian(x, &jacobian);
  auto lu = MakeLinearSolver("klu");
  Vec rhs = Vec::Ones(l.size()), solution;
  lu->Factorize(jacobian);  // analysis outside the measurement
  double factorize_solve_cpu = 0.0;
  const double factorize_solve = repeat_for(
      [&] {
        lu->Factorize(jacobian);
        lu->Solve(rhs, &solution);
      },
      &factorize_solve_cpu);
  // The work of one Newton iteration without the per-step overhead (start point, initial
  // residual, bookkeeping): factorisation, solve, and the trial residual with its Jacobian in
  // one pass (the next iteration's right-hand side and matrix), with the solver under test.
  auto linear = MakeLinearSolver(linear_solver);
  linear->SetStructure(system.structure());
  Vec residual, step_dx;
  system.Residual(x, &residual);
  linear->Factorize(jacobian);
  double iteration_kernel_cpu = 0.0;
  const double iteration_kernel = repeat_for(
      [&] {
        linear->Factorize(jacobian);
        linear->Solve(residual, &step_dx);
        system.ResidualAndJacobian(x, &residual, &jacobian);
      },
      &iteration_kernel_cpu);
  // The parts of the kernel, and the separate evaluations the one pass replaces.
  const double jacobian_us = 1e6 * repeat_for([&] { system.Jacobian(x, &jacobian); });
  const double residual_us = 1e6 * repeat_for([&] { system.Residual(x, &residual); });
  const double residual_and_jacobian_us =
      1e6 * repeat_for([&] { system.ResidualAndJacobian(x, &residual, &jacobian); });
  const double factorize_us = 1e6 * repeat_for([&] { linear->Factorize(jacobian); });
  const double solve_us = 1e6 * repeat_for([&] { linear->Solve(residual, &step_dx); });
  for (auto _ : state) {
    lu->Factorize(jacobian);
    lu->Solve(rhs, &solution);
    benchmark::DoNotOptimize(solution.data());
  }
  state.counters["jacobian_us"] = jacobian_us;
  state.counters["residual_us"] = residual_us;
  state.counters["residual_and_jacobian_us"] = residual_and_jacobian_us;
  state.counters["factorize_us"] = factorize_us;
  state.counters["solve_us"] = solve_us;
  if (const CondensedSolverStats* stats = CondensedStats(*linear)) {
    const double factorizations =
        std::max(1, stats->condensed_factorizations + stats->fallback_factorizations);
    state.counters["fallback_share"] = stats->fallback_factorizations / factorizations;
    state.counters["refinement_sweeps_per_solve"] = stats->refinement_sweeps / factorizations;
  }
  state.counters["newton_iterations"] = result.counts.iterations;
  state.counters["per_newton_iteration_us"] = per_iteration * 1e6;
  state.counters["lu_factorize_solve_us"] = factorize_solve * 1e6;
  state.counters["ratio"] = per_iteration / factorize_solve;
  state.counters["iteration_kernel_us"] = iteration_kernel * 1e6;
  state.counters["kernel_ratio"] = iteration_kernel / factorize_solve;
  state.counters["ratio_cpu"] = per_solve_cpu / result.counts.iterations / factorize_solve_cpu;
  state.counters["kernel_ratio_cpu"] = iteration_kernel_cpu / factorize_solve_cpu;
}

void IterationOverFactorizationBlock(benchmark::State& state, const std::string& linear_solver) {
  const Problem p = MakeProblem("block", {{"n", std::to_string(state.range(0))}});
  StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load), p.scales};
  StartPoint cold;
  cold.kind = StartKind::kCold;
  IterationOverFactorization(state, step, cold, linear_solver);
}

void IterationOverFactorizationArchCurved(benchmark::State& state,
                                          const std::string& linear_solver) {
  const Problem p = MakeProblem("arch-curved");
  ImplicitFb reference(Options("klu"));
  PathRecorder recorder;
  PathOptions options;
  options.arc_length = p.arc_length;
  options.max_steps = static_cast<int>(state.range(0));
  TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), reference, options, &recorder);
  StepProblem step{p.model.get(), recorder.steps.back().state,
                   StepConstraint::ArcLength(p.arc_length), p.scales};
  StartPoint start;
  start.du = recorder.steps.back().increment.du;
  start.dlambda = recorder.steps.back().increment.dlambda;
  start.r = recorder.steps.back().state.r;
  IterationOverFactorization(state, step, start, linear_solver);
}

void RegisterAll() {
  // The default first, then the full-system LU for comparison (n = 400 only with the default:
  // KLU needs minutes there).
  for (const std::string solver : {"cholmod", "klu"}) {
    auto* b =
        bench::RegisterWithRange(("BM_BlockColdSolve/" + solver).c_str(), BlockColdSolve, solver);
    for (int n : {25, 50, 100, 200}) b->Arg(n);
    if (solver == "cholmod") b->Arg(400);
    b->Unit(benchmark::kMillisecond);
  }
  for (const std::string solver : {"cholmod", "klu"}) {
    bench::RegisterWithRange(("BM_ArchCurvedWarmStep/" + solver).c_str(), ArchCurvedWarmStep,
                             solver)
        ->Arg(100)
        ->Arg(1000)
        ->Unit(benchmark::kMicrosecond);
  }
  for (const std::string solver : {"cholmod", "klu"}) {
    for (const std::string problem : {"arch-curved", "arch-flat"}) {
      bench::RegisterWithRange(("BM_ArchPath/" + problem + "/" + solver).c_str(), ArchPath, problem,
                               solver)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(3);
    }
  }
  for (const std::string solver : {"cholmod", "klu"}) {
    // n = 200 with klu would repeat 15 LU factorisations of 2 s each: the LU comparator is
    // measured by the cholmod case anyway.
    auto* block = bench::RegisterWithRange(("BM_IterationOverFactorizationBlock/" + solver).c_str(),
                                           IterationOverFactorizationBlock, solver);
    block->Arg(50)->Unit(benchmark::kMillisecond);
    if (solver == "cholmod") block->Arg(200);
    bench::RegisterWithRange(("BM_IterationOverFactorizationArchCurved/" + solver).c_str(),
                             IterationOverFactorizationArchCurved, solver)
        ->Arg(100)
        ->Arg(1000)
        ->Unit(benchmark::kMicrosecond);
  }
}

}  // namespace
}  // namespace cb

int main(int argc, char** argv) {
  cb::RegisterAll();
  cb::bench::UseOneBlasThreadUnlessAsked();
  benchmark::AddCustomContext("blas", cb::BlasDescription(cb::LoadedBlas()));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
