#include "harness/cli.h"

#include <contactbench_build_info.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/csv.h"
#include "formulations/registry.h"
#include "harness/commands.h"
#include "harness/fclib_export.h"
#include "harness/interrupt.h"
#include "harness/memory_budget.h"
#include "harness/options.h"
#include "harness/plot_command.h"
#include "harness/records_doc.h"
#include "harness/rerun.h"
#include "harness/run_json.h"
#include "harness/suggest.h"
#include "io/fclib_file.h"
#include "io/problem_file.h"
#include "problems/problem.h"
#include "solvers/equation_solver.h"
#include "solvers/linear_solver.h"

namespace cb::harness {

namespace {

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

// Writes the problem as a problem file: the suite's JSON, or an FCLIB global problem.
int Export(const RunArguments& a) {
  const Problem problem = LoadProblem(a);
  const std::filesystem::path out(a.out);
  std::error_code ec;
  if (std::filesystem::is_directory(out, ec)) {
    throw InputError("--out: '" + a.out + "' is a directory; give the problem file's name");
  }
  const std::filesystem::path dir = out.parent_path().empty() ? "." : out.parent_path();
  if (a.export_format == "fclib") {
    if (!io::FclibAvailable()) {
      throw InputError(
          "--format fclib: this build has no HDF5 (install libhdf5-dev, "
          "scripts/packages.txt, and configure again)");
    }
    PrepareOutput(dir.string());
    const std::string what = ExportFclib(a, problem);
    std::fprintf(stderr, "%s -> %s (FCLIB, mu = 0; %s)\n", problem.name.c_str(), a.out.c_str(),
                 what.c_str());
    return kExitOk;
  }
  if (a.export_step) throw UsageError("--step: only with --format fclib");
  std::string text;
  try {
    text = io::ProblemToJson(problem);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  PrepareOutput(dir.string());
  std::ofstream file(out, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw InputError("--out: cannot write '" + a.out + "'");
  std::fprintf(stderr, "%s -> %s\n", problem.name.c_str(), a.out.c_str());
  return kExitOk;
}

// Prints the record files' columns (docs/records.md's generated section).
int Schema() {
  std::cout << RecordsMarkdown();
  return kExitOk;
}

int Execute(Command command, const RunArguments& a, RunJson* record);

// `contactbench rerun DIR --out NEW`: the recorded command again (rerun.h), refused when it
// would not be the same run unless --force.
int Rerun(const RunArguments& a) {
  const RerunPlan plan = PlanRerun(a.operand, a.out, a.overwrite);
  if (!plan.differences.empty()) {
    const std::string listed = "\n  " + Join(plan.differences, "\n  ");
    if (!a.force) {
      throw InputError("rerun: refused, '" + a.operand + "' was made otherwise:" + listed +
                       "\n(--force reruns it anyway)");
    }
    std::fprintf(stderr, "rerun: --force: rerunning although%s\n", listed.c_str());
  }
  const CommandInfo* command = FindCommand(plan.command);
  const RunArguments arguments = ParseArguments(command->command, plan.arguments);
  RunJson record;
  record.command_line = {RunningBinary(), plan.command};
  record.command_line.insert(record.command_line.end(), plan.arguments.begin(),
                             plan.arguments.end());
  record.command = plan.command;
  record.rerun_of = a.operand;
  return Execute(command->command, arguments, &record);
}

int Execute(Command command, const RunArguments& a, RunJson* record) {
  switch (command) {
    case kList:
      return List();
    case kRun:
      return RunCommand(a, record);
    case kCompare:
      return CompareCommand(a, record);
    case kExport:
      return Export(a);
    case kSchema:
      return Schema();
    case kPlot:
      return RunPlotScript(a);
    case kRerun:
      return Rerun(a);
  }
  return kExitBadArguments;
}

std::vector<std::string> CommandNames() {
  std::vector<std::string> names;
  for (const CommandInfo& c : Commands()) names.emplace_back(c.name);
  names.emplace_back("help");
  return names;
}

// `contactbench --version`: the version and the commit of the build (as run.json records them).
int Version() {
  const std::string commit = CONTACTBENCH_COMMIT;
  std::cout << "contactbench " << CONTACTBENCH_VERSION
            << (commit.empty() ? " (commit unknown)" : " (commit " + commit + ")") << "\n";
  return kExitOk;
}

}  // namespace

int Main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  const CommandInfo* command = nullptr;
  try {
    if (args.empty()) {  // an argument error: the usage goes to standard error
      std::cerr << UsageText();
      return kExitBadArguments;
    }
    if (args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
      std::cout << UsageText();
      return kExitOk;
    }
    if (args[0] == "--version") return Version();
    command = FindCommand(args[0]);
    if (command == nullptr) {
      throw UsageError("unknown command '" + args[0] + "'" + DidYouMean(args[0], CommandNames()) +
                       " (valid: " + Join(CommandNames()) + ")");
    }
    const RunArguments a =
        ParseArguments(command->command, std::vector<std::string>(args.begin() + 1, args.end()));
    if (a.help) {
      std::cout << CommandHelp(*command);
      return kExitOk;
    }
    RunJson record;
    record.command_line.assign(argv, argv + argc);
    record.command = command->name;
    return Execute(command->command, a, &record);
  } catch (const InputError& e) {
    std::cerr << "contactbench: " << e.what() << "\n";
    return kExitBadArguments;
  } catch (const UsageError& e) {
    std::cerr << "contactbench: " << e.what() << "\n";
    if (command == nullptr) {
      std::cerr << "`contactbench help` shows the usage of every command.\n";
    } else {
      std::cerr << Synopsis(*command) << "`contactbench " << command->name
                << " --help` describes the options.\n";
    }
    return kExitBadArguments;
  } catch (const Interrupted& e) {
    std::cerr << "contactbench: " << e.what()
              << "; the run stopped (the records written before are kept whole)\n";
    return kExitInterrupted;
  } catch (const std::bad_alloc&) {
    std::cerr << "contactbench: out of memory while " << Activity::Current()
              << " (the records written before are kept whole)\n";
    return kExitFailure;
  } catch (const WriteError& e) {
    std::cerr << "contactbench: " << e.what()
              << "; the run stopped (the records written before are kept whole)\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "contactbench: error: " << e.what() << "\n";
    return kExitFailure;
  } catch (...) {
    // Not a std::exception (a backend's own type): still a failure with a status, not abort().
    std::cerr << "contactbench: error: an exception of unknown type\n";
    return kExitFailure;
  }
}

}  // namespace cb::harness
