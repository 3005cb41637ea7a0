#include "harness/cli.h"

#include <contactbench_build_info.h>

#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/csv.h"
#include "harness/cli_commands.h"
#include "harness/commands.h"
#include "harness/interrupt.h"
#include "harness/memory_budget.h"
#include "harness/options.h"
#include "harness/plot_command.h"
#include "harness/plugins.h"
#include "harness/run_json.h"
#include "harness/suggest.h"

namespace cb::harness {

namespace {

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

int Execute(Command command, const RunArguments& a, RunJson* record) {
  switch (command) {
    case kList:
      return ListCommand();
    case kRun:
      return RunCommand(a, record);
    case kCompare:
      return CompareCommand(a, record);
    case kExport:
      return ExportCommand(a);
    case kSchema:
      return SchemaCommand();
    case kPlot:
      return RunPlotScript(a);
    case kRerun:
      return RerunCommand(a);
  }
  return kExitBadArguments;
}

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
    const std::vector<std::string> options(args.begin() + 1, args.end());
    for (const auto& plugin : PluginPaths(options)) LoadPlugin(plugin);  // before the parser
    const RunArguments a = ParseArguments(command->command, options);
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
