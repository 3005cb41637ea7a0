#include "harness/cli.h"

#include <algorithm>
#include <atomic>
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
#include "path/path.h"
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
  contactbench run --problem NAME --formulation NAME --out DIR
                   [--solver newton|dogleg|quasi-newton] [--eta 1|2|3|4]
                   [--steps N] [--arc-length THETA] [--start warm|cold] [--tol T]
                   [--linear-solver NAME] [--max-cutbacks N] [--no-kinks]
                   [--time-limit SECONDS] [--set KEY=VALUE ...] [--option KEY=VALUE ...]
  contactbench help

run writes DIR/steps.csv, iterations.csv, kinks.csv, solution.csv and contacts.csv.
--set changes a problem parameter (see `contactbench list` for each problem's parameters);
--option passes a formulation's own setting (e.g. implicit-fb gamma_tol, rho_min).
Exit status: 0 every step verified; 2 bad arguments; 3 stopped on a failure (records kept);
4 interrupted (records kept).
)";

struct RunArguments {
  std::string problem;
  std::string formulation;
  std::string out;
  FormulationConfig config;
  std::optional<int> steps;
  std::optional<double> arc_length;
  StartKind start = StartKind::kWarm;
  double tolerance = 1e-8;
  int max_cutbacks = 6;
  bool locate_kinks = true;
  double time_limit = 0.0;
  std::map<std::string, std::string> settings;
};

double ParseNumber(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
    return v;
  } catch (const std::exception&) {
    throw UsageError(option + ": '" + text + "' is not a number");
  }
}

int ParseInteger(const std::string& option, const std::string& text) {
  const double v = ParseNumber(option, text);
  if (v != static_cast<double>(static_cast<int>(v))) {
    throw UsageError(option + ": '" + text + "' is not an integer");
  }
  return static_cast<int>(v);
}

RunArguments ParseRun(const std::vector<std::string>& args) {
  RunArguments a;
  auto value = [&](std::size_t& i) -> const std::string& {
    if (i + 1 >= args.size()) throw UsageError(args[i] + " needs a value");
    return args[++i];
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& o = args[i];
    if (o == "--problem") {
      a.problem = value(i);
    } else if (o == "--formulation") {
      a.formulation = value(i);
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
    } else if (o == "--start") {
      const std::string& s = value(i);
      if (s == "warm") {
        a.start = StartKind::kWarm;
      } else if (s == "cold") {
        a.start = StartKind::kCold;
      } else {
        throw UsageError("--start: '" + s + "' is not one of: warm, cold");
      }
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
    } else if (o == "--max-cutbacks") {
      a.max_cutbacks = ParseInteger(o, value(i));
      if (a.max_cutbacks < 0) throw UsageError("--max-cutbacks: must be >= 0");
    } else if (o == "--no-kinks") {
      a.locate_kinks = false;
    } else if (o == "--time-limit") {
      a.time_limit = ParseNumber(o, value(i));
      if (!(a.time_limit > 0.0)) throw UsageError("--time-limit: must be positive");
    } else if (o == "--option") {
      const std::string& kv = value(i);
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw UsageError("--option: expected KEY=VALUE, got '" + kv + "'");
      }
      a.config.options[kv.substr(0, eq)] = kv.substr(eq + 1);
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
  if (a.problem.empty())
    throw UsageError("--problem is required (valid: " + Join(ProblemNames()) + ")");
  if (a.formulation.empty()) {
    throw UsageError("--formulation is required (valid: " + Join(FormulationNames()) + ")");
  }
  if (a.out.empty()) throw UsageError("--out DIR is required");
  return a;
}

int List() {
  std::cout << "problems:\n";
  for (const auto& info : ProblemRegistry()) {
    std::cout << "  " << info.name << "  " << info.description << "\n";
    for (const auto& e : info.defaults().entries()) {
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

// Refuses an output directory that cannot be written before any work starts.
void PrepareOutput(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw UsageError("--out: cannot create '" + dir + "': " + ec.message());
  const std::string probe = dir + "/.contactbench_write_test";
  {
    std::ofstream f(probe);
    if (!f) throw UsageError("--out: '" + dir + "' is not writable");
  }
  std::filesystem::remove(probe, ec);
}

int Run(const std::vector<std::string>& args) {
  RunArguments a = ParseRun(args);
  Problem problem;
  std::unique_ptr<Formulation> formulation;
  try {
    problem = MakeProblem(a.problem, a.settings);
    formulation = MakeFormulation(a.formulation, a.config);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  PrepareOutput(a.out);

  PathOptions options;
  options.arc_length = a.arc_length.value_or(problem.arc_length);
  options.max_steps = a.steps.value_or(problem.steps);
  options.tolerance = a.tolerance;
  options.start = a.start;
  options.max_cutbacks = a.max_cutbacks;
  options.locate_kinks = a.locate_kinks;
  options.controls.time_limit_s = a.time_limit;
  options.controls.interrupted = [] { return g_interrupted.load(); };
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  RunRecorder recorder(a.out, problem,
                       {problem.name, formulation->name(), formulation->solver(),
                        formulation->settings(), ToString(a.start)});
  const State initial = ZeroState(*problem.model);
  PathSummary summary;
  if (problem.loading == LoadingKind::kFixedLoad) {
    summary = SolveFixedLoad(*problem.model, problem.scales, initial, problem.load, *formulation,
                             options, &recorder);
  } else {
    summary = TraceArcLengthPath(*problem.model, problem.scales, initial, *formulation, options,
                                 &recorder);
  }
  recorder.WriteSnapshot(summary.final_state, summary.accepted_steps);
  std::fprintf(stderr, "%s %s: %s (%d accepted steps, %d attempts, %d kinks) -> %s\n",
               problem.name.c_str(), formulation->name().c_str(), summary.message.c_str(),
               summary.accepted_steps, summary.attempts, summary.kinks, a.out.c_str());
  if (summary.status == Status::kStoppedByCaller) return kExitInterrupted;
  if (summary.status != Status::kConverged) return kExitFailure;
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
    throw UsageError("unknown command '" + command + "' (valid: list, run, help)");
  } catch (const UsageError& e) {
    std::cerr << "contactbench: " << e.what() << "\n" << kUsage;
    return kExitBadArguments;
  } catch (const std::exception& e) {
    std::cerr << "contactbench: error: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace cb::harness
