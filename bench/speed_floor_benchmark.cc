// Speed to the floor (docs/findings.md, "Speed to the floor"): one cold fixed-load solve of P1
// `block` (n = 100, 200, 400) and of `hertz-3d` (n = nz = 16, 24, 40) by implicit-fb as it runs
// by default (Newton on the contact unknowns, docs/method.md "Reduced Newton"), by implicit-fb's
// full route (option reduced_newton=0) and by PETSc's petsc-ssls and petsc-rsls, with the
// repetitions interleaved at random (--benchmark_enable_random_interleaving, on unless given) so
// that the ratios are taken on one machine state.
//
// implicit-fb's default solve reports its time split (details of RunReducedStepSolver):
//   setup_s          everything before the factorisation (the patterns, the start, the first
//                    Jacobian) and b~_c's forward sweep: the solve's time less the three below;
//   factorization_s  the factorisation of A + D0 with the contact dofs last (and T);
//   iterations_s     the Newton iterations on the contact unknowns;
//   recovery_s       the interior of the answer (one backward sweep);
// and its floor, floor_s = factorization_s + iterations x (one forward + one backward sweep),
// the cost of a Newton method that factorises once and sweeps twice per iteration, measured in
// the same solve; time_over_floor is the solve's time over it.
//
// Every answer is judged by the verdict (tolerance 1e-8); one that fails ends its benchmark with
// SkipWithError, untimed. A formulation this build lacks is skipped with the reason, and so, for
// this benchmark's time budget, are PETSc's on hertz-3d above n = 24 (44-46 s per solve there
// on the 2-core machine of results/README.md; its 3-D LU grows faster than d).
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

#include "bench_support.h"
#include "core/timer.h"
#include "formulations/registry.h"
#include "problems/problem.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

constexpr double kTolerance = 1e-8;
constexpr double kTimeLimitS = 1800.0;
constexpr int kLargestPetscHertzMesh = 24;

// A formulation as this benchmark runs it: the registry name and its options.
struct Variant {
  std::string label;
  std::string formulation;
  std::map<std::string, std::string> options;
};

std::vector<Variant> Variants() {
  return {{"implicit-fb", "implicit-fb", {}},
          {"implicit-fb-full", "implicit-fb", {{"reduced_newton", "0"}}},
          {"petsc-ssls", "petsc-ssls", {}},
          {"petsc-rsls", "petsc-rsls", {}}};
}

double Detail(const StepResult& result, const std::string& key) {
  const auto it = result.details.find(key);
  return it == result.details.end() ? -1.0 : std::stod(it->second);
}

// The time split and the floor of a reduced solve that took `solve_s` (see the top of the file).
void AddTimeSplit(const StepResult& result, double solve_s, benchmark::State& state) {
  const double factorization = Detail(result, "factorization_s");
  const double iterations = Detail(result, "iterations_s");
  const double recovery = Detail(result, "recovery_s");
  if (factorization < 0.0 || iterations < 0.0 || recovery < 0.0) return;  // not the reduced route
  const double sweeps = Detail(result, "forward_sweep_s") + Detail(result, "backward_sweep_s");
  const double floor = factorization + result.counts.iterations * sweeps;
  state.counters["setup_s"] = solve_s - factorization - iterations - recovery;
  state.counters["factorization_s"] = factorization;
  state.counters["iterations_s"] = iterations;
  state.counters["recovery_s"] = recovery;
  state.counters["floor_s"] = floor;
  state.counters["time_over_floor"] = solve_s / floor;
}

void ColdSolve(benchmark::State& state, const std::string& problem, const Variant& variant) {
  const int n = static_cast<int>(state.range(0));
  std::map<std::string, std::string> settings = {{"n", std::to_string(n)}};
  if (problem == "hertz-3d") settings["nz"] = std::to_string(n);
  if (problem == "hertz-3d" && n > kLargestPetscHertzMesh &&
      variant.formulation.rfind("petsc", 0) == 0) {
    state.SkipWithError(
        "not run: 44-46 s per solve at n = 24, and its 3-D LU grows faster than d (time budget)");
    return;
  }
  try {
    const Problem p = MakeProblem(problem, settings);
    StartPoint cold;
    const StepProblem step = bench::ColdFixedLoadStep(p, &cold);
    FormulationConfig config;
    config.options = variant.options;
    std::string why;
    if (!MakeFormulation(variant.formulation, config)->Accepts(step, &why)) {
      state.SkipWithError(("not run: " + why).c_str());
      return;
    }
    SolveControls controls;
    controls.time_limit_s = kTimeLimitS;
    StepResult result;
    Verdict verdict;
    double seconds = 0.0;
    for (auto _ : state) {
      auto formulation = MakeFormulation(variant.formulation, config);
      Stopwatch clock;
      result = formulation->Solve(step, cold, controls);
      seconds = clock.Seconds();
      state.SetIterationTime(seconds);
      benchmark::DoNotOptimize(result.point.du.data());
      verdict = Judge(step, result.point, kTolerance);
      if (!verdict.verified) {
        state.SkipWithError(bench::VerdictMessage(verdict, result, false).c_str());
        return;
      }
    }
    state.counters["n"] = n;
    state.counters["d"] = step.num_dofs();
    state.counters["nc"] = step.num_pairs();
    bench::AddSolveCounters(result, verdict, state);
    AddTimeSplit(result, seconds, state);
  } catch (const std::exception& e) {
    state.SkipWithError((std::string("error: ") + e.what()).c_str());
  }
}

// Random interleaving on unless the command line chooses.
std::vector<char*> WithInterleaving(int argc, char** argv) {
  static std::string flag = "--benchmark_enable_random_interleaving=true";
  std::vector<char*> args(argv, argv + argc);
  bool given = false;
  for (int k = 1; k < argc; ++k) {
    given = given || std::string(argv[k]).rfind("--benchmark_enable_random_interleaving", 0) == 0;
  }
  if (!given) args.push_back(flag.data());
  return args;
}

}  // namespace
}  // namespace cb

int main(int argc, char** argv) {
  using namespace cb;
  std::vector<char*> args = WithInterleaving(argc, argv);
  int count = static_cast<int>(args.size());
  if (!bench::StartFormulationBenchmarks(&count, args.data())) return 1;
  const std::vector<std::pair<std::string, std::vector<int>>> cases = {{"block", {100, 200, 400}},
                                                                       {"hertz-3d", {16, 24, 40}}};
  for (const auto& one_case : cases) {
    const std::string problem = one_case.first;
    for (const Variant& variant : Variants()) {
      const FormulationInfo* info = FindFormulation(variant.formulation);
      const bool built = info != nullptr && info->available;
      for (int n : one_case.second) {
        auto* b = bench::RegisterWithRange((problem + "/" + variant.label).c_str(),
                                           [problem, variant, built](benchmark::State& state) {
                                             if (!built) {
                                               state.SkipWithError("not run: not built");
                                               return;
                                             }
                                             ColdSolve(state, problem, variant);
                                           });
        b->ArgName("n")->Arg(n)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
      }
    }
  }
  bench::RunRegisteredBenchmarks();
  return 0;
}
