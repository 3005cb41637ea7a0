// Helpers shared by the formulation benchmarks (formulation_step_benchmark.cc,
// scaling_benchmark.cc): the machine description for the JSON context, the verdict as a
// message, and the resident-memory probes of /proc/self.
#pragma once

#include <benchmark/benchmark.h>
#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/blas_info.h"
#include "formulations/registry.h"
#include "path/path.h"
#include "problems/problem.h"
#include "step/formulation.h"
#include "verdict/verdict.h"

namespace cb::bench {

// Registers a benchmark whose repetitions (--benchmark_repetitions, scripts/run_bench.sh) are
// reported with their range: Google Benchmark's aggregates are mean, median, stddev and cv;
// min and max are added, so that the records keep the median with its spread.
template <typename... Arguments>
benchmark::internal::Benchmark* RegisterWithRange(Arguments&&... arguments) {
  return benchmark::RegisterBenchmark(std::forward<Arguments>(arguments)...)
      ->ComputeStatistics(
          "min", [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); })
      ->ComputeStatistics("max", [](const std::vector<double>& v) {
        return *std::max_element(v.begin(), v.end());
      });
}

// Whether the serial benchmarks time this formulation: built, and not a distributed one (its
// registry entry), which on one process is its serial counterpart's method through PETSc's
// SNES and has its own scale benchmark (docs/scale-out.md).
inline bool InSerialBenchmarks(const FormulationInfo& info) {
  return info.available && !info.distributed;
}

// The CPU model from /proc/cpuinfo: Google Benchmark's own context has the number of CPUs and
// their clock, not the model, which the comparison report states.
inline std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}

// One BLAS thread unless the environment says otherwise: on this shared 2-core VM OpenBLAS's
// second thread gains nothing measurable on a quiet machine and, spinning for a core another
// job holds, multiplies the wall time of the P1 solve by 3-4 under load (docs/findings.md). The
// context's "blas" line says how many threads ran.
inline void UseOneBlasThreadUnlessAsked() {
  if (!BlasThreadsChosenByEnvironment()) SetBlasThreads(1);
}

inline void AddMachineContext() {
  benchmark::AddCustomContext("cpu_model", CpuModel());
  benchmark::AddCustomContext("hardware_threads",
                              std::to_string(std::thread::hardware_concurrency()));
  benchmark::AddCustomContext("blas", BlasDescription(LoadedBlas()));
}

// The opening of a formulation benchmark's main: Google Benchmark takes its arguments (false
// when one is not its own: the program should exit 1), one BLAS thread unless asked, and the
// machine and the verdict's tolerance in the context.
inline bool StartFormulationBenchmarks(int* argc, char** argv) {
  benchmark::Initialize(argc, argv);
  if (benchmark::ReportUnrecognizedArguments(*argc, argv)) return false;
  UseOneBlasThreadUnlessAsked();
  AddMachineContext();
  benchmark::AddCustomContext("verdict_tolerance", "1e-08");
  return true;
}

// The close of a benchmark's main: runs what was registered; main returns 0.
inline void RunRegisteredBenchmarks() {
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}

// The counters every formulation benchmark records of a solve: its work counts and the
// verdict's equilibrium and complementarity residuals.
inline void AddSolveCounters(const StepResult& result, const Verdict& verdict,
                             benchmark::State& state) {
  state.counters["iterations"] = result.counts.iterations;
  state.counters["residual_evals"] = result.counts.residual_evals;
  state.counters["jacobian_evals"] = result.counts.jacobian_evals;
  state.counters["linear_solves"] = result.counts.linear_solves;
  state.counters["eq_res"] = verdict.eq_res;
  state.counters["comp_res"] = verdict.comp_res;
}

// The fixed-load step of `p` to its load from the unloaded state, and the cold start of report
// 5.1 (each formulation's fixed start; du and r as SolveFixedLoad passes them) in *cold.
inline StepProblem ColdFixedLoadStep(const Problem& p, StartPoint* cold) {
  StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load), p.scales};
  cold->kind = StartKind::kCold;
  cold->du = Vec::Zero(step.num_dofs());
  cold->dlambda = p.load;
  cold->r = Vec::Zero(step.num_pairs());
  return step;
}

// Why an answer is not accepted, for SkipWithError.
inline std::string VerdictMessage(const Verdict& v, const StepResult& r, bool reversed) {
  char text[256];
  std::snprintf(text, sizeof(text), "%s: eq %.2g comp %.2g feas %.2g step %.2g (%s, %d iterations)",
                reversed ? "turned back on the reference path" : "not verified", v.eq_res,
                v.comp_res, v.feas_res, v.step_res, r.message.c_str(), r.counts.iterations);
  return text;
}

// A field of /proc/self/status in kB ("VmRSS", "VmHWM"); -1 if unreadable.
inline double StatusKb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1));
  }
  return -1.0;
}

// Peak resident memory of one solve: free heap is returned to the system (malloc_trim) and the
// high-water mark VmHWM reset to the current RSS (writing 5 to /proc/self/clear_refs, Linux >=
// 4.0), so that VmHWM after the solve is the peak during it and VmHWM - RSS before is what the
// solve added. Without clear_refs (another kernel, a sandbox) `reset` is false and the peak is
// the process's since its start.
class PeakMemory {
 public:
  void Start() {
    malloc_trim(0);
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    clear.flush();
    reset_ = static_cast<bool>(clear);
    rss_before_kb_ = StatusKb("VmRSS");
  }
  // Peak RSS since Start [MB] and its increase over the RSS at Start [MB].
  double PeakMb() const { return StatusKb("VmHWM") / 1024.0; }
  double IncreaseMb() const { return (StatusKb("VmHWM") - rss_before_kb_) / 1024.0; }
  bool reset() const { return reset_; }

 private:
  double rss_before_kb_ = 0.0;
  bool reset_ = false;
};

}  // namespace cb::bench
