#include "harness/cli.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "formulations/registry.h"
#include "harness/records.h"
#include "harness/snapshots.h"
#include "io/problem_file.h"
#include "model/complementarity_model.h"
#include "path/path.h"
#include "path/replay.h"
#include "problems/problem.h"
#include "solvers/linear_solver.h"

namespace cb::harness {

namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void OnSignal(int) { g_interrupted.store(true); }

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// A usage error: reported with exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr const char* kUsage = R"(usage:
  contactbench list
  contactbench run (--problem NAME | --problem-file F.json) --formulation NAME --out DIR
                   [--solver newton|dogleg|quasi-newton] [--eta 1|2|3|4]
                   [--steps N] [--arc-length THETA] [--start warm|cold|near] [--tol T]
                   [--near-offset DELTA]
                   [--linear-solver NAME] [--max-cutbacks N] [--no-kinks]
                   [--bifurcations off|detect|switch] [--save-every N]
                   [--time-limit SECONDS] [--set KEY=VALUE ...] [--option KEY=VALUE ...]
  contactbench compare (--problem NAME | --problem-file F.json) --out DIR
                   [--formulations A,B,...] [--starts warm,cold]
                   [--mode replay|free] [--reference NAME] [--steps N] [--arc-length THETA]
                   [--solver S] [--eta E] [--tol T] [--linear-solver NAME] [--time-limit SECONDS]
                   [--set KEY=VALUE ...] [--option FORMULATION:KEY=VALUE ...]
  contactbench export (--problem NAME | --problem-file F.json) [--set KEY=VALUE ...] --out F.json
  contactbench help

run writes DIR/steps.csv, iterations.csv, kinks.csv, critical.csv, solution.csv and
contacts.csv (the final state), and the saved states (every --save-every N-th step, each
critical point, the final state) in snapshots.csv, snapshot_contacts.csv and vtk/*.vtu, *.pvd.
--bifurcations (default detect): watch the sign of the bordered stiffness's determinant and
record limit and bifurcation points in critical.csv; switch also locates the first
bifurcation point and continues on the other branch.
--set changes a problem parameter (see `contactbench list` for each problem's parameters);
--option passes a formulation's own setting (e.g. implicit-fb gamma_tol, rho_min); with
compare, prefix it with the formulation's name.
compare: every formulation x start traces the SAME steps (replay mode: each step starts from
the reference path's previous accepted state; the reference is traced first by --reference,
default implicit-fb) or its own path (free mode), into one long-format steps.csv and
iterations.csv, the reference path's kinks.csv, and runs.csv (one row per formulation x start).
--problem-file reads a problem file (a truss, a plane-stress Q4 mesh, or an LCP; see
docs/problem-files.md); its --set keys are length_scale, force_scale and load or arc_length,
steps. export writes a named problem (or a problem file, normalised) as a problem file.
Exit status: 0 every step verified; 2 bad arguments; 3 stopped on a failure (records kept);
4 interrupted (records kept).
--start near (fixed-load problems, e.g. P1): the solve starts from the solution of implicit-fb
(eta 1, Newton) perturbed by the relative offset DELTA (default 1e-2) with a fixed pattern,
as the report's section 5.1 starts eta case 3 near the solution.
)";

struct RunArguments {
  std::string problem;
  std::string problem_file;
  std::string formulation;                // run
  std::vector<std::string> formulations;  // compare
  std::vector<StartKind> starts;          // compare
  std::string mode = "replay";            // compare
  std::string reference = "implicit-fb";  // compare
  std::string out;
  FormulationConfig config;
  // --option KEY=VALUE (run) or FORMULATION:KEY=VALUE, by formulation ("" for unprefixed).
  std::map<std::string, std::map<std::string, std::string>> options;
  std::optional<int> steps;
  std::optional<double> arc_length;
  StartKind start = StartKind::kWarm;
  bool start_near = false;   // run --start near: a warm start near a reference solution
  double near_offset = 1e-2;
  double tolerance = 1e-8;
  int max_cutbacks = 6;
  bool locate_kinks = true;
  BifurcationMode bifurcations = BifurcationMode::kDetect;
  int save_every = 0;
  double time_limit = 0.0;
  std::map<std::string, std::string> settings;
};

double ParseNumber(const std::string& option, const std::string& text) {
  double v = 0.0;
  try {
    std::size_t used = 0;
    v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw UsageError(option + ": '" + text + "' is not a number");
  }
  if (!std::isfinite(v)) throw UsageError(option + ": must be finite, got '" + text + "'");
  return v;
}

int ParseInteger(const std::string& option, const std::string& text) {
  const double v = ParseNumber(option, text);
  // Range first: converting a double outside int's range is undefined.
  if (v != std::floor(v) || v < INT_MIN || v > INT_MAX) {
    throw UsageError(option + ": '" + text + "' is not an integer in range");
  }
  return static_cast<int>(v);
}

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::size_t end = comma == std::string::npos ? text.size() : comma;
    if (end > start) items.push_back(text.substr(start, end - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

StartKind ParseStart(const std::string& option, const std::string& s) {
  if (s == "warm") return StartKind::kWarm;
  if (s == "cold") return StartKind::kCold;
  throw UsageError(option + ": '" + s + "' is not one of: warm, cold");
}

// Arguments of `run` (compare = false) or `compare` (compare = true).
RunArguments ParseArguments(const std::vector<std::string>& args, bool compare) {
  RunArguments a;
  std::vector<std::string> seen;  // options that take one value: refused when repeated
  auto value = [&](std::size_t& i) -> const std::string& {
    if (i + 1 >= args.size()) throw UsageError(args[i] + " needs a value");
    if (args[i] != "--set" && args[i] != "--option") {
      if (std::find(seen.begin(), seen.end(), args[i]) != seen.end()) {
        throw UsageError(args[i] + " is given twice");
      }
      seen.push_back(args[i]);
    }
    return args[++i];
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& o = args[i];
    if (o == "--problem") {
      a.problem = value(i);
    } else if (o == "--problem-file") {
      a.problem_file = value(i);
    } else if (o == "--formulation" && !compare) {
      a.formulation = value(i);
    } else if (o == "--formulations" && compare) {
      a.formulations = SplitList(value(i));
      for (const auto& f : a.formulations) {
        const auto names = FormulationNames();
        if (std::find(names.begin(), names.end(), f) == names.end()) {
          throw UsageError("--formulations: unknown formulation '" + f +
                           "' (valid: " + Join(names) + ")");
        }
      }
    } else if (o == "--starts" && compare) {
      for (const auto& s : SplitList(value(i))) a.starts.push_back(ParseStart(o, s));
    } else if (o == "--mode" && compare) {
      a.mode = value(i);
      if (a.mode != "replay" && a.mode != "free") {
        throw UsageError("--mode: '" + a.mode + "' is not one of: replay, free");
      }
    } else if (o == "--reference" && compare) {
      a.reference = value(i);
    } else if (o == "--out") {
      a.out = value(i);
    } else if (o == "--solver") {
      a.config.solver = value(i);
      const auto names = EquationSolverNames();
      if (std::find(names.begin(), names.end(), a.config.solver) == names.end()) {
        throw UsageError("--solver: unknown solver '" + a.config.solver +
                         "' (valid: " + Join(names) + ")");
      }
    } else if (o == "--eta") {
      a.config.eta = ParseInteger(o, value(i));
      if (a.config.eta < 1 || a.config.eta > 4) throw UsageError("--eta: must be 1, 2, 3 or 4");
    } else if (o == "--steps") {
      a.steps = ParseInteger(o, value(i));
      if (*a.steps <= 0) throw UsageError("--steps: must be a positive integer");
    } else if (o == "--arc-length") {
      a.arc_length = ParseNumber(o, value(i));
      if (!(*a.arc_length > 0.0)) throw UsageError("--arc-length: must be positive");
    } else if (o == "--start" && !compare) {
      const std::string& start = value(i);
      a.start_near = start == "near";
      a.start = a.start_near ? StartKind::kWarm : ParseStart(o, start);
    } else if (o == "--near-offset" && !compare) {
      a.near_offset = ParseNumber(o, value(i));
      if (!(a.near_offset >= 0.0)) throw UsageError("--near-offset: must be >= 0");
    } else if (o == "--tol") {
      a.tolerance = ParseNumber(o, value(i));
      if (!(a.tolerance > 0.0)) throw UsageError("--tol: must be positive");
    } else if (o == "--linear-solver") {
      a.config.solver_options.linear_solver = value(i);
      const auto names = LinearSolverNames();
      if (std::find(names.begin(), names.end(), a.config.solver_options.linear_solver) ==
          names.end()) {
        throw UsageError("--linear-solver: unknown '" + a.config.solver_options.linear_solver +
                         "' (valid: " + Join(names) + ")");
      }
    } else if (o == "--max-cutbacks" && !compare) {
      a.max_cutbacks = ParseInteger(o, value(i));
      if (a.max_cutbacks < 0) throw UsageError("--max-cutbacks: must be >= 0");
    } else if (o == "--no-kinks" && !compare) {
      a.locate_kinks = false;
    } else if (o == "--bifurcations" && !compare) {
      const std::string& mode = value(i);
      if (!ParseBifurcationMode(mode, &a.bifurcations)) {
        throw UsageError("--bifurcations: unknown '" + mode + "' (valid: off, detect, switch)");
      }
    } else if (o == "--save-every" && !compare) {
      a.save_every = ParseInteger(o, value(i));
      if (a.save_every < 0) throw UsageError("--save-every: must be >= 0");
    } else if (o == "--time-limit") {
      a.time_limit = ParseNumber(o, value(i));
      if (!(a.time_limit > 0.0)) throw UsageError("--time-limit: must be positive");
    } else if (o == "--option") {
      const std::string& kv = value(i);
      const auto eq = kv.find('=');
      const auto colon = kv.find(':');
      const bool prefixed = colon != std::string::npos && colon < eq;
      if (eq == std::string::npos || eq == 0 || (compare && !prefixed)) {
        throw UsageError(std::string("--option: expected ") +
                         (compare ? "FORMULATION:KEY=VALUE" : "KEY=VALUE") + ", got '" + kv + "'");
      }
      const std::string owner = prefixed ? kv.substr(0, colon) : "";
      const std::string key = prefixed ? kv.substr(colon + 1, eq - colon - 1) : kv.substr(0, eq);
      a.options[owner][key] = kv.substr(eq + 1);
    } else if (o == "--set") {
      const std::string& kv = value(i);
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw UsageError("--set: expected KEY=VALUE, got '" + kv + "'");
      }
      a.settings[kv.substr(0, eq)] = kv.substr(eq + 1);
    } else {
      throw UsageError("unknown option '" + o + "'");
    }
  }
  if (!a.problem.empty() && !a.problem_file.empty()) {
    throw UsageError("give either --problem or --problem-file, not both");
  }
  if (a.problem.empty() && a.problem_file.empty()) {
    throw UsageError("--problem NAME or --problem-file F.json is required (valid names: " +
                     Join(ProblemNames()) + ")");
  }
  if (!compare && a.formulation.empty()) {
    throw UsageError("--formulation is required (valid: " + Join(FormulationNames()) + ")");
  }
  if (compare && a.formulations.empty()) {
    for (const auto& info : FormulationRegistry()) {
      if (info.available) a.formulations.push_back(info.name);
    }
  }
  if (compare && a.starts.empty()) a.starts = {StartKind::kWarm};
  if (a.out.empty()) throw UsageError("--out DIR is required");
  for (const auto& [owner, kv] : a.options) {
    if (owner.empty()) continue;
    const auto names = FormulationNames();
    if (std::find(names.begin(), names.end(), owner) == names.end()) {
      throw UsageError("--option: unknown formulation '" + owner + "' (valid: " + Join(names) +
                       ")");
    }
  }
  return a;
}

// The configuration of formulation `name`: the common settings plus its own --option values.
FormulationConfig ConfigFor(const RunArguments& a, const std::string& name) {
  FormulationConfig config = a.config;
  for (const auto& owner : {std::string(), name}) {
    auto it = a.options.find(owner);
    if (it != a.options.end()) config.options.insert(it->second.begin(), it->second.end());
  }
  return config;
}

PathOptions MakePathOptions(const RunArguments& a, const Problem& problem) {
  PathOptions options;
  options.arc_length = a.arc_length.value_or(problem.arc_length);
  options.max_steps = a.steps.value_or(problem.steps);
  options.tolerance = a.tolerance;
  options.start = a.start;
  options.max_cutbacks = a.max_cutbacks;
  options.locate_kinks = a.locate_kinks;
  options.bifurcations = a.bifurcations;
  options.controls.time_limit_s = a.time_limit;
  options.controls.interrupted = [] { return g_interrupted.load(); };
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  return options;
}

// The problem's first step, as Trace takes it: what a formulation is asked to Accept before the
// problem is run (capability depends on the model and the kind of step, not on the path).
StepProblem FirstStep(const Problem& problem, const PathOptions& options) {
  const StepConstraint constraint =
      problem.loading == LoadingKind::kFixedLoad
          ? StepConstraint::FixedLoad(problem.load)
          : StepConstraint::ArcLength(options.arc_length, options.lambda_weight);
  return {problem.model.get(), ZeroState(*problem.model), constraint, problem.scales};
}

// Runs the problem's loading (the fixed-load solve, or the arc-length path) with a formulation.
PathSummary Trace(const Problem& problem, Formulation& formulation, const PathOptions& options,
                  PathObserver* observer, const State* guess = nullptr) {
  const State initial = ZeroState(*problem.model);
  if (problem.loading == LoadingKind::kFixedLoad) {
    return SolveFixedLoad(*problem.model, problem.scales, initial, problem.load, formulation,
                          options, observer, guess);
  }
  return TraceArcLengthPath(*problem.model, problem.scales, initial, formulation, options,
                            observer);
}

int List() {
  std::cout << "problems:\n";
  for (const auto& info : ProblemRegistry()) {
    std::cout << "  " << info.name << "  " << info.description << "\n";
    // Hold the defaults: a range-for over a member of a temporary would dangle (before C++23).
    const Parameters defaults = info.defaults();
    for (const auto& e : defaults.entries()) {
      std::cout << "      " << e.name << " = " << e.value << "   " << e.doc << "\n";
    }
  }
  std::cout << "formulations:\n";
  for (const auto& info : FormulationRegistry()) {
    std::cout << "  " << info.name << (info.available ? "" : " (not built)") << "  "
              << info.description << "\n";
  }
  std::cout << "solvers (--solver):\n  " << Join(EquationSolverNames()) << "\n";
  std::cout << "linear solvers (--linear-solver):\n  " << Join(LinearSolverNames()) << "\n";
  return kExitOk;
}

// Refuses an output directory that cannot be written before any work starts: created if
// missing, then probed with a file (permissions alone do not tell: root, read-only mounts).
void PrepareOutput(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw UsageError("--out: cannot create the directory '" + dir + "': " + ec.message());
  if (!std::filesystem::is_directory(dir, ec)) {
    throw UsageError("--out: '" + dir + "' exists and is not a directory");
  }
  const std::string probe = dir + "/.contactbench_write_test";
  {
    std::ofstream f(probe);
    if (!f) throw UsageError("--out: the directory '" + dir + "' is not writable");
  }
  std::filesystem::remove(probe, ec);
}

// The problem of --problem NAME or --problem-file F, with --set applied. Bad input (an unknown
// name, a bad setting, an invalid problem file) is a usage error.
Problem LoadProblem(const RunArguments& a) {
  try {
    if (!a.problem_file.empty()) return io::LoadProblemFile(a.problem_file, a.settings);
    return MakeProblem(a.problem, a.settings);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// The last accepted state of a problem that is not a body: an LCP's z and w = M z + q.
void WriteComplementaritySnapshot(const std::string& dir, const Problem& problem,
                                  const State& state, int step) {
  if (problem.body != nullptr ||
      dynamic_cast<const ComplementarityModel*>(problem.model.get()) == nullptr) {
    return;
  }
  Vec w;
  problem.model->InternalForce(state.u, &w);
  CsvWriter solution(dir + "/solution.csv", {"step", "index", "z", "w"});
  for (int i = 0; i < problem.model->num_dofs(); ++i) {
    CsvWriter::Row row;
    row << step << i << state.u[i] << w[i];
    solution.Write(row);
  }
}

int Run(const std::vector<std::string>& args) {
  RunArguments a = ParseArguments(args, false);
  Problem problem = LoadProblem(a);
  std::unique_ptr<Formulation> formulation;
  try {
    formulation = MakeFormulation(a.formulation, ConfigFor(a, a.formulation));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  PrepareOutput(a.out);
  const PathOptions options = MakePathOptions(a, problem);
  std::string refusal;
  if (!formulation->Accepts(FirstStep(problem, options), &refusal)) {
    throw UsageError(refusal + " (problem '" + problem.name + "')");
  }

  // --start near: the reference solution, perturbed by near_offset (relative, per entry, with
  // the fixed pattern sin(i + 1) so that runs are reproducible).
  std::optional<State> near;
  if (a.start_near) {
    if (problem.loading != LoadingKind::kFixedLoad) {
      throw UsageError("--start near: only for fixed-load problems; '" + problem.name +
                       "' is traced by arc length");
    }
    auto reference = MakeFormulation("implicit-fb", FormulationConfig());
    const PathSummary solved = Trace(problem, *reference, options, nullptr);
    if (solved.status != Status::kConverged) {
      std::fprintf(stderr, "contactbench: --start near: the reference solve failed (%s)\n",
                   solved.message.c_str());
      return kExitFailure;
    }
    near = solved.final_state;
    for (int i = 0; i < near->u.size(); ++i) near->u[i] *= 1.0 + a.near_offset * std::sin(i + 1.0);
    for (int i = 0; i < near->r.size(); ++i) near->r[i] *= 1.0 + a.near_offset * std::sin(i + 2.0);
  }
  RecordFiles files(a.out);
  RunRecorder recorder(&files, problem,
                       {problem.name, formulation->name(), formulation->solver(),
                        formulation->settings(), a.start_near ? "near" : ToString(a.start), "run"},
                       problem.loading == LoadingKind::kFixedLoad ? 1 : options.max_steps);
  {
    // The problem's parameters, reconstruction choices included, beside its records.
    CsvWriter parameters(a.out + "/parameters.csv", {"problem", "name", "value", "doc"});
    for (const auto& e : problem.parameters.entries()) {
      CsvWriter::Row row;
      row << problem.name << e.name << e.value << e.doc;
      parameters.Write(row);
    }
    CsvWriter::Row dofs, pairs;
    dofs << problem.name << "num_dofs" << std::to_string(problem.model->num_dofs())
         << "d, displacement unknowns (model size)";
    pairs << problem.name << "num_pairs" << std::to_string(problem.model->num_pairs())
          << "nc, contact pairs (model size)";
    parameters.Write(dofs);
    parameters.Write(pairs);
  }
  SnapshotWriter snapshots(a.out, problem, a.save_every);
  ObserverTee observers({&recorder, &snapshots});
  const PathSummary summary =
      Trace(problem, *formulation, options, &observers, near ? &*near : nullptr);
  WriteSnapshot(a.out, problem, summary.final_state, summary.accepted_steps);
  snapshots.Save(summary.final_state, summary.accepted_steps, "final");
  WriteComplementaritySnapshot(a.out, problem, summary.final_state, summary.accepted_steps);
  std::fprintf(stderr,
               "%s %s: %s (%d accepted steps, %d attempts, %d kinks, %d limit points, "
               "%d bifurcation points, %d branch switches) -> %s\n",
               problem.name.c_str(), formulation->name().c_str(), summary.message.c_str(),
               summary.accepted_steps, summary.attempts, summary.kinks, summary.limit_points,
               summary.bifurcations, summary.branch_switches, a.out.c_str());
  if (summary.status == Status::kStoppedByCaller) return kExitInterrupted;
  if (summary.status != Status::kConverged) return kExitFailure;
  return kExitOk;
}

int Compare(const std::vector<std::string>& args) {
  RunArguments a = ParseArguments(args, true);
  Problem problem = LoadProblem(a);
  std::vector<std::unique_ptr<Formulation>> formulations;
  std::unique_ptr<Formulation> reference;
  try {
    for (const auto& name : a.formulations) {
      formulations.push_back(MakeFormulation(name, ConfigFor(a, name)));
    }
    reference = MakeFormulation(a.reference, ConfigFor(a, a.reference));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  PrepareOutput(a.out);
  PathOptions options = MakePathOptions(a, problem);
  const StepProblem first = FirstStep(problem, options);
  const int total = problem.loading == LoadingKind::kFixedLoad ? 1 : options.max_steps;
  RecordFiles files(a.out);
  CsvWriter runs(a.out + "/runs.csv", {"problem", "formulation", "solver", "start", "mode",
                                       "settings", "status", "attempts", "accepted", "message",
                                       "time_limit_s", "tolerance"});

  // The reference path: the work every formulation is given in replay mode (warm start,
  // cut-backs and kinks as in `run`). Its kinks are the ones recorded.
  PathRecorder path;
  if (a.mode == "replay") {
    options.start = StartKind::kWarm;
    RunRecorder kinks_only(&files, problem,
                           {problem.name, "reference:" + reference->name(), reference->solver(),
                            reference->settings(), "warm", "reference"},
                           total);
    struct KinkTee final : PathObserver {
      PathRecorder* path;
      RunRecorder* kinks;
      void OnAttempt(const StepAttempt& at) override { path->OnAttempt(at); }
      void OnKink(const KinkRecord& k) override {
        path->OnKink(k);
        kinks->OnKink(k);
      }
    } tee;
    tee.path = &path;
    tee.kinks = &kinks_only;
    const PathSummary s = Trace(problem, *reference, options, &tee);
    std::fprintf(stderr, "reference %s: %s\n", reference->name().c_str(), s.message.c_str());
    if (path.states.empty()) {
      std::fprintf(stderr, "contactbench: the reference path has no verified step to replay\n");
      return kExitFailure;
    }
  }

  for (const auto& formulation : formulations) {
    for (StartKind start : a.starts) {
      CsvWriter::Row row;
      row << problem.name << formulation->name() << formulation->solver() << ToString(start)
          << a.mode << formulation->settings();
      std::string why;
      if (!formulation->Accepts(first, &why)) {
        std::fprintf(stderr, "skipping %s: %s\n", formulation->name().c_str(), why.c_str());
        row << "skipped" << 0 << 0 << why << a.time_limit << a.tolerance;
        runs.Write(row);
        continue;
      }
      RunRecorder recorder(&files, problem,
                           {problem.name, formulation->name(), formulation->solver(),
                            formulation->settings(), ToString(start), a.mode},
                           a.mode == "replay" ? static_cast<int>(path.states.size()) : total);
      PathOptions run_options = options;
      run_options.start = start;
      run_options.locate_kinks = false;  // the reference path's kinks are the recorded ones
      const PathSummary s =
          a.mode == "replay" ? ReplayPath(*problem.model, problem.scales, ZeroState(*problem.model),
                                          path, *formulation, run_options, &recorder)
                             : Trace(problem, *formulation, run_options, &recorder);
      row << ToString(s.status) << recorder.attempts() << recorder.accepted() << s.message
          << a.time_limit << a.tolerance;
      runs.Write(row);
      if (s.status == Status::kStoppedByCaller) return kExitInterrupted;
    }
  }
  std::fprintf(stderr, "compare: records in %s\n", a.out.c_str());
  return kExitOk;
}

// export: --problem NAME or --problem-file F, --set, --out FILE (a problem file).
int Export(const std::vector<std::string>& args) {
  RunArguments a;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& o = args[i];
    if (o != "--problem" && o != "--problem-file" && o != "--set" && o != "--out") {
      throw UsageError("export: unknown option '" + o +
                       "' (valid: --problem, --problem-file, --set, --out)");
    }
    if (i + 1 >= args.size()) throw UsageError(o + " needs a value");
    const std::string& v = args[++i];
    if (o == "--set") {
      const auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw UsageError("--set: expected KEY=VALUE, got '" + v + "'");
      }
      a.settings[v.substr(0, eq)] = v.substr(eq + 1);
      continue;
    }
    std::string& field = o == "--problem" ? a.problem : o == "--out" ? a.out : a.problem_file;
    if (!field.empty()) throw UsageError(o + " is given twice");
    field = v;
  }
  if (!a.problem.empty() && !a.problem_file.empty()) {
    throw UsageError("give either --problem or --problem-file, not both");
  }
  if (a.problem.empty() && a.problem_file.empty()) {
    throw UsageError("--problem NAME or --problem-file F.json is required (valid names: " +
                     Join(ProblemNames()) + ")");
  }
  if (a.out.empty()) throw UsageError("--out F.json is required");
  const Problem problem = LoadProblem(a);
  std::string text;
  try {
    text = io::ProblemToJson(problem);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  const std::filesystem::path out(a.out);
  std::error_code ec;
  if (std::filesystem::is_directory(out, ec)) {
    throw UsageError("--out: '" + a.out + "' is a directory; give the problem file's name");
  }
  const std::filesystem::path dir = out.parent_path().empty() ? "." : out.parent_path();
  PrepareOutput(dir.string());
  std::ofstream file(out, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw UsageError("--out: cannot write '" + a.out + "'");
  std::fprintf(stderr, "%s -> %s\n", problem.name.c_str(), a.out.c_str());
  return kExitOk;
}

}  // namespace

int Main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
      std::cout << kUsage;
      return args.empty() ? kExitBadArguments : kExitOk;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    if (command == "list") return List();
    if (command == "run") return Run(args);
    if (command == "compare") return Compare(args);
    if (command == "export") return Export(args);
    throw UsageError("unknown command '" + command + "' (valid: list, run, compare, export, help)");
  } catch (const UsageError& e) {
    std::cerr << "contactbench: " << e.what() << "\n" << kUsage;
    return kExitBadArguments;
  } catch (const std::exception& e) {
    std::cerr << "contactbench: error: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace cb::harness
