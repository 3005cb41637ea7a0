// One loading step of P2 `arch-flat` and P3 `arch-curved` for every formulation of this build,
// warm and cold, in replay mode (COMPARISON.md "Same work for everyone"): each problem's
// reference path is traced once by implicit-fb (Newton, eta case 1, the problem's default
// theta and step count, kinks located, as `contactbench compare` does), and every formulation
// solves the SAME steps of it.
//
// Representative steps (chosen from the reference path at start-up, so they follow the
// problem's parameters; the step number is in the benchmark's name and the `step` counter):
//  early          step 10: early on the path, small displacements (with the default
//                 reconstruction the first contact closes before it, at step 8);
//  first-contact  the first step whose answer has a pair in contact (g/L < -r/R): the contact
//                 status changes inside the step, so the warm start's prediction is off;
//  last           the last step of the default path (deepest into the loading).
// A path without contact (possible for some reconstruction parameters) has no first-contact
// benchmark; the JSON context says where each step lies (`<problem>_steps`).
//
// Step k is solved as ReplayPath solves it: from the reference state after step k - 1 with the
// reference step's own constraint (its theta) and, for a warm start, the prediction the
// reference step was given and this formulation's own backend state from step k - 1 (solved
// first, with the same start kind, outside the measurement: that solve also does the symbolic
// analysis, as the previous step of a path does). Each measured iteration is one Solve; the
// verdict is judged after every solve outside the measured time (manual timing), and an answer
// that fails it (or turns back on the path) ends the benchmark with SkipWithError, untimed.
//
// Every solve has the comparison runs' time limit (5 s, scripts/run_compare.sh). A formulation
// that refuses the step (Formulation::Accepts: e.g. an energy NLP cannot express an arc-length
// step) is registered and skipped with its reason, so the output lists it. A time-budget
// choice of this benchmark, not a capability: dense SLSQP (nlopt-mpcc, seconds per P3 step)
// runs one iteration per repetition.
//
// Counters: iterations (NLopt: objective evaluations), residual_evals, jacobian_evals,
// linear_solves, the verdict's eq_res, comp_res, feas_res, step_res, n_contact of the answer,
// step, lambda at the end of the step, d (degrees of freedom) and nc (contact pairs), and
// time_vs_implicit_fb: the mean time of a solve over implicit-fb's on the same step and start
// measured earlier in the same run (registered first, as the registry lists it first), so that
// peers are compared on one machine state (absent when implicit-fb was filtered out).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <any>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.h"
#include "core/timer.h"
#include "formulations/registry.h"
#include "path/path.h"
#include "path/replay.h"
#include "problems/problem.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

constexpr double kTolerance = 1e-8;  // the verdict's, as in every run
constexpr double kTimeLimitS = 5.0;  // per solve, as in scripts/run_compare.sh
constexpr int kEarlyStep = 10;

// implicit-fb's mean solve time per benchmark (problem/start/step), for time_vs_implicit_fb.
std::map<std::string, double>& ImplicitFbTimes() {
  static std::map<std::string, double> times;
  return times;
}

// A problem's reference path, traced once.
struct Reference {
  Problem problem;
  PathRecorder path;
  std::vector<int> n_contact;  // per accepted step
  PathSummary summary;
};

class ContactTee final : public PathObserver {
 public:
  explicit ContactTee(Reference* ref) : ref_(ref) {}
  void OnAttempt(const StepAttempt& at) override {
    ref_->path.OnAttempt(at);
    if (at.accepted) ref_->n_contact.push_back(at.n_contact);
  }
  void OnKink(const KinkRecord& k) override { ref_->path.OnKink(k); }

 private:
  Reference* ref_;
};

std::unique_ptr<Reference> TraceReference(const std::string& problem_name) {
  auto ref = std::make_unique<Reference>();
  ref->problem = MakeProblem(problem_name);
  PathOptions options;
  options.arc_length = ref->problem.arc_length;
  options.max_steps = ref->problem.steps;
  options.tolerance = kTolerance;
  auto reference = MakeFormulation("implicit-fb", FormulationConfig{});
  ContactTee tee(ref.get());
  ref->summary = TraceArcLengthPath(*ref->problem.model, ref->problem.scales,
                                    ZeroState(*ref->problem.model), *reference, options, &tee);
  return ref;
}

// Step k (1-based) of the replay: its problem and start, exactly as ReplayPath builds them.
StepProblem ReplayStep(const Reference& ref, int k) {
  return ReplayedStep(*ref.problem.model, ref.problem.scales, ZeroState(*ref.problem.model),
                      ref.path, k, 1.0);
}

StartPoint ReplayStart(const Reference& ref, int k, StartKind kind, std::any warm_state) {
  StartPoint start = ReplayedStart(ReplayStep(ref, k), ref.path, k, kind);
  start.warm_state = std::move(warm_state);
  return start;
}

// Accepted as in replay mode: verified, and not the other root of (33) (pointing against the
// reference step).
bool Reversed(const Reference& ref, int k, const StepPoint& p) {
  return ReplayedReversed(ref.path, k, p, 1.0);
}

void StepBenchmark(benchmark::State& state, const Reference* ref, const std::string& name,
                   StartKind start_kind, int k) {
  const std::string key = ref->problem.name + "/" + ToString(start_kind) + "/" + std::to_string(k);
  try {
    auto formulation = MakeFormulation(name, FormulationConfig{});
    std::string why;
    if (!formulation->Accepts(ReplayStep(*ref, k), &why)) {
      state.SkipWithError(("not run: " + why).c_str());
      return;
    }
    SolveControls controls;
    controls.time_limit_s = kTimeLimitS;

    // Step k - 1: the pattern analysis and the backend state a warm start of step k may reuse.
    std::any warm_state;
    {
      const StepProblem step = ReplayStep(*ref, k - 1);
      const StepResult r =
          formulation->Solve(step, ReplayStart(*ref, k - 1, start_kind, {}), controls);
      if (Judge(step, r.point, kTolerance).verified && !Reversed(*ref, k - 1, r.point)) {
        warm_state = r.warm_state;
      }
    }

    const StepProblem step = ReplayStep(*ref, k);
    const StartPoint start = ReplayStart(*ref, k, start_kind, warm_state);
    StepResult result;
    Verdict verdict;
    double total_s = 0.0;
    for (auto _ : state) {
      Stopwatch clock;
      result = formulation->Solve(step, start, controls);
      const double seconds = clock.Seconds();
      state.SetIterationTime(seconds);
      total_s += seconds;
      // A pointer, not a double: GCC 12 mis-handles DoNotOptimize(double&) (google/benchmark#903).
      benchmark::DoNotOptimize(result.point.du.data());
      verdict = Judge(step, result.point, kTolerance);
      const bool reversed = Reversed(*ref, k, result.point);
      if (!verdict.verified || reversed) {
        state.SkipWithError(bench::VerdictMessage(verdict, result, reversed).c_str());
        break;
      }
    }
    if (state.error_occurred()) return;
    Vec phi;
    step.model->Gaps(step.base.u + result.point.du, &phi);
    bench::AddSolveCounters(result, verdict, state);
    state.counters["feas_res"] = verdict.feas_res;
    state.counters["step_res"] = verdict.step_res;
    state.counters["n_contact"] = CountContacts(step, -phi, result.point.r);
    state.counters["step"] = k;
    state.counters["lambda"] = step.base.lambda + result.point.dlambda;
    state.counters["d"] = step.num_dofs();
    state.counters["nc"] = step.num_pairs();
    const double mean_s = total_s / static_cast<double>(state.iterations());
    if (name == "implicit-fb") ImplicitFbTimes()[key] = mean_s;
    if (auto it = ImplicitFbTimes().find(key); it != ImplicitFbTimes().end()) {
      state.counters["time_vs_implicit_fb"] = mean_s / it->second;
    }
  } catch (const std::exception& e) {
    state.SkipWithError((std::string("error: ") + e.what()).c_str());
  }
}

// The representative steps (see the top of the file), as (label, k) with 2 <= k <= steps.
std::vector<std::pair<std::string, int>> RepresentativeSteps(const Reference& ref) {
  const int steps = static_cast<int>(ref.path.steps.size());
  std::vector<std::pair<std::string, int>> out;
  if (steps < 2) return out;
  const int early = std::min(kEarlyStep, steps);
  out.emplace_back("early", early);
  const auto contact =
      std::find_if(ref.n_contact.begin(), ref.n_contact.end(), [](int n) { return n > 0; });
  if (contact != ref.n_contact.end()) {
    const int k = std::max(2, static_cast<int>(contact - ref.n_contact.begin()) + 1);
    if (k != early) out.emplace_back("first-contact", k);
  }
  if (steps != out.back().second) out.emplace_back("last", steps);
  return out;
}

}  // namespace
}  // namespace cb

int main(int argc, char** argv) {
  using namespace cb;
  if (!bench::StartFormulationBenchmarks(&argc, argv)) return 1;
  benchmark::AddCustomContext("time_limit_per_solve_s", "5");

  static std::map<std::string, std::unique_ptr<Reference>> references;
  for (const std::string problem : {"arch-flat", "arch-curved"}) {
    Stopwatch clock;
    auto ref = TraceReference(problem);
    const auto steps = RepresentativeSteps(*ref);
    std::string where =
        std::to_string(ref->path.steps.size()) + " accepted steps (" + ref->summary.message + ")";
    for (const auto& [label, k] : steps) {
      where += "; " + label + " = step " + std::to_string(k) + " (lambda " +
               std::to_string(ref->path.steps[k - 1].state.lambda) + ", " +
               std::to_string(ref->n_contact[k - 1]) + " pairs in contact)";
    }
    std::fprintf(stderr, "reference %s: %s [%.2f s]\n", problem.c_str(), where.c_str(),
                 clock.Seconds());
    benchmark::AddCustomContext(problem + "_steps", where);
    for (const auto& info : FormulationRegistry()) {
      if (!bench::InSerialBenchmarks(info)) continue;
      for (const StartKind start : {StartKind::kWarm, StartKind::kCold}) {
        for (const auto& [label, k] : steps) {
          const std::string name = "FormulationStep/" + problem + "/" + info.name + "/" +
                                   ToString(start) + "/" + label + "/step:" + std::to_string(k);
          auto* b =
              bench::RegisterWithRange(name.c_str(), StepBenchmark, ref.get(), info.name, start, k);
          b->UseManualTime()->Unit(benchmark::kMicrosecond);
          // Time budget: dense SLSQP takes seconds per P3 step, so one solve per repetition is
          // the measurement.
          if (info.name == "nlopt-mpcc") b->Iterations(1)->Repetitions(1);
        }
      }
    }
    references[problem] = std::move(ref);
  }
  bench::RunRegisteredBenchmarks();
  return 0;
}
