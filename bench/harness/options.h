// The command line of `contactbench`: one table of options drives the parser of every
// subcommand and produces the usage text and each subcommand's --help, so that what is parsed
// and what is documented cannot drift apart.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "formulations/common/config.h"
#include "path/path.h"
#include "problems/problem_path.h"

namespace cb::harness {

// A usage error: reported with exit status 2 and the command's usage.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Bad input that is no mistake in the form of the command line (a bad problem file, a problem
// the formulation refuses, an output directory that cannot be used): exit status 2 as well,
// but reported by its message alone, since the usage would not help.
struct InputError : UsageError {
  using UsageError::UsageError;
};

// The subcommands, as bits of a set.
enum Command : unsigned {
  kList = 1u << 0,
  kRun = 1u << 1,
  kCompare = 1u << 2,
  kExport = 1u << 3,
  kSchema = 1u << 4,
  kPlot = 1u << 5,
  kRerun = 1u << 6,
};

struct CommandInfo {
  Command command;
  const char* name;
  const char* summary;  // what it does (plain text, wrapped when printed)
  // The one argument that is not an option ("OUT_DIR"), required; nullptr: none.
  const char* operand = nullptr;
  const char* operand_help = nullptr;
};
// In the order of the usage text.
const std::vector<CommandInfo>& Commands();
// nullptr for an unknown name.
const CommandInfo* FindCommand(const std::string& name);

// What the options of a command set.
struct RunArguments {
  bool help = false;
  std::string problem;
  std::string problem_file;
  std::string problem_dir;  // compare --problem-dir: directories and files, comma-separated
  std::string formulation;  // run
  std::vector<std::string> formulations;  // compare
  std::vector<StartKind> starts;          // compare
  std::string mode = "replay";            // compare
  std::string reference = "implicit-fb";  // compare
  std::string out;
  std::string export_format = "json";  // export: json or fclib
  std::optional<int> export_step;      // export --format fclib --step N: a path's step N
  bool overwrite = false;              // run, compare: replace an earlier run's records in `out`
  bool force = false;         // rerun: run even when the build, a library or an input differs
  bool allow_memory = false;  // run the problem even when its memory estimate exceeds the limit
  FormulationConfig config;
  // --option KEY=VALUE (run) or FORMULATION:KEY=VALUE, by formulation ("" for unprefixed).
  std::map<std::string, std::map<std::string, std::string>> options;
  std::string petsc_options;  // --petsc-options: the PETSc formulations' options string
  std::optional<int> steps;
  std::optional<double> arc_length;
  StartKind start = StartKind::kWarm;
  bool start_near = false;  // run --start near: a warm start near a reference solution
  int start_guess = 0;      // run --start guess:K: from the FCLIB file's /guesses/K (0: not)
  double near_offset = 1e-2;
  // The library's defaults (problem_path.h), so that a run without options traces as a
  // program using DefaultPathOptions does.
  double tolerance = PathOptions().tolerance;
  int max_cutbacks = PathOptions().max_cutbacks;
  bool locate_kinks = PathOptions().locate_kinks;
  BifurcationMode bifurcations = kDefaultBifurcationMode;
  int save_every = 0;
  double time_limit = 0.0;
  int repeat = 1;  // compare --repeat: every timed solve done this many times
  std::map<std::string, std::string> settings;
  std::string operand;           // the command's operand (plot: the run's directory)
  std::optional<int> plot_step;  // plot --step
  std::string figures;           // plot --figures
};

// Whether a command needs an option.
enum class Need {
  kOptional,
  kRequired,
  kProblem,  // exactly one of the options marked so (--problem, --problem-file)
};

struct Option {
  const char* name;         // "--steps"
  const char* placeholder;  // "N"; "" for a flag, which takes no value
  unsigned commands;        // the Commands that take it
  Need need;
  bool repeatable;  // may be given more than once (--set); otherwise refused when repeated
  const char* help;
  // The valid values, listed in the help and in errors (nullptr: any).
  std::vector<std::string> (*choices)();
  // Parses and checks `value` ("" for a flag) into the arguments; throws UsageError naming
  // the option.
  void (*parse)(const Option& option, const std::string& value, RunArguments* arguments);
};
// In the order of the usage text. An option name may have two entries for disjoint commands
// (export's --out is a file, run's a directory).
const std::vector<Option>& Options();

// "--steps N", or the name alone for a flag.
std::string NameAndValue(const Option& option);

// The arguments of `command` (the command line after its name), checked: unknown, repeated or
// missing options and bad values throw UsageError. With --help, returns at once with `help`.
// `out_optional`: --out may be left out (the Python module keeps the records in memory then,
// commands.h).
RunArguments ParseArguments(Command command, const std::vector<std::string>& args,
                            bool out_optional = false);

// "a, b, c".
std::string Join(const std::vector<std::string>& items, const std::string& separator = ", ");

// The usage of every command, with the exit statuses (`contactbench help`).
std::string UsageText();
// A command's usage line(s).
std::string Synopsis(const CommandInfo& command);
// `contactbench COMMAND --help`: the usage, what it does, and each of its options.
std::string CommandHelp(const CommandInfo& command);

}  // namespace cb::harness
