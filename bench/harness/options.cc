#include "harness/options.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "formulations/implicit_fb/eta_equation.h"
#include "formulations/registry.h"
#include "harness/suggest.h"
#include "problems/problem.h"
#include "solvers/linear_solver.h"

namespace cb::harness {

namespace {

bool Contains(const std::vector<std::string>& items, const std::string& item) {
  return std::find(items.begin(), items.end(), item) != items.end();
}

[[noreturn]] void Refuse(const Option& option, const std::string& why) {
  throw UsageError(std::string(option.name) + ": " + why);
}

// --- values --------------------------------------------------------------------------------

// Decimal notation only ("16", "-2.5", "1e-3"): strtod would also read hexadecimal ("0x10"),
// "inf" and "nan", which no option means.
bool IsDecimalNumber(const std::string& text) {
  std::size_t i = 0;
  auto digits = [&] {
    const std::size_t start = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
    return i > start;
  };
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  bool mantissa = digits();
  if (i < text.size() && text[i] == '.') {
    ++i;
    mantissa = digits() || mantissa;
  }
  if (!mantissa) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == text.size();
}

double ParseNumber(const Option& option, const std::string& text) {
  const std::string lower = [&] {
    std::string l = text;
    for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return l;
  }();
  if (lower.find("inf") != std::string::npos) Refuse(option, "must be finite, got '" + text + "'");
  if (!IsDecimalNumber(text)) Refuse(option, "'" + text + "' is not a decimal number");
  errno = 0;
  const double v = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(v)) Refuse(option, "must be finite, got '" + text + "'");
  // A value below the smallest normal double is rounded to a subnormal or to 0 (ERANGE): say
  // so, rather than use a number that is not the one written.
  if (v != 0.0 && !std::isnormal(v)) {
    Refuse(option, "'" + text + "' is too small: below the smallest normal double (2.2e-308)");
  }
  if (errno == ERANGE && v == 0.0) {
    Refuse(option, "'" + text + "' is too small: it underflows to 0");
  }
  return v;
}

int ParseInteger(const Option& option, const std::string& text) {
  const bool decimal_integer =
      !text.empty() &&
      std::all_of(text.begin() + (text[0] == '-' || text[0] == '+' ? 1 : 0), text.end(),
                  [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }) &&
      text != "-" && text != "+";
  if (!decimal_integer) Refuse(option, "'" + text + "' is not a decimal integer");
  const double v = ParseNumber(option, text);
  // Range first: converting a double outside int's range is undefined.
  if (v < INT_MIN || v > INT_MAX) Refuse(option, "'" + text + "' is not an integer in range");
  return static_cast<int>(v);
}

double PositiveNumber(const Option& option, const std::string& text) {
  const double v = ParseNumber(option, text);
  if (!(v > 0.0)) Refuse(option, "must be positive");
  return v;
}

// The verdict's tolerance: positive and at most kMaxVerdictTolerance.
double VerdictTolerance(const Option& option, const std::string& text) {
  const double v = PositiveNumber(option, text);
  if (v > kMaxVerdictTolerance) {
    std::ostringstream bound;
    bound << kMaxVerdictTolerance;
    Refuse(option, "must be at most " + bound.str() + " (the verdict's range), got '" + text + "'");
  }
  return v;
}

int NonNegativeInteger(const Option& option, const std::string& text) {
  const int v = ParseInteger(option, text);
  if (v < 0) Refuse(option, "must be >= 0");
  return v;
}

// The comma-separated items of `text`, each without the blanks around it ("a, b" as "a,b": a
// list typed with the spaces of prose); empty items are dropped.
std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    std::size_t end = comma == std::string::npos ? text.size() : comma;
    while (start < end && (text[start] == ' ' || text[start] == '\t')) ++start;
    while (end > start && (text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
    if (end > start) items.push_back(text.substr(start, end - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

// A comma-separated list with no empty item ("a,,b", ",", "" are refused: an empty list would
// silently mean the default).
std::vector<std::string> NonEmptyList(const Option& option, const std::string& text) {
  std::vector<std::string> items = SplitList(text);
  if (items.empty()) Refuse(option, "the list '" + text + "' names nothing");
  if (std::count(text.begin(), text.end(), ',') + 1 != static_cast<long>(items.size())) {
    Refuse(option, "the list '" + text + "' has an empty name");
  }
  return items;
}

// `value` if it is one of the option's choices.
const std::string& Choice(const Option& option, const std::string& value) {
  const std::vector<std::string> valid = option.choices();
  if (!Contains(valid, value))
    Refuse(option,
           "unknown '" + value + "'" + DidYouMean(value, valid) + " (valid: " + Join(valid) + ")");
  return value;
}

// KEY=VALUE into (key, value).
std::pair<std::string, std::string> KeyValue(const Option& option, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0) Refuse(option, "expected KEY=VALUE, got '" + kv + "'");
  return {kv.substr(0, eq), kv.substr(eq + 1)};
}

// [FORMULATION:]KEY=VALUE: a setting of the formulation named, or of every formulation.
void FormulationOption(const Option& option, const std::string& text, bool prefix_required,
                       RunArguments* a) {
  const auto colon = text.find(':');
  const auto eq = text.find('=');
  const bool prefixed = colon != std::string::npos && colon < eq;
  if (prefix_required && !prefixed) {
    Refuse(option, "expected FORMULATION:KEY=VALUE, got '" + text + "'");
  }
  const std::string owner = prefixed ? text.substr(0, colon) : "";
  if (prefixed && !Contains(FormulationNames(), owner)) {
    Refuse(option, "unknown formulation '" + owner + "'" + DidYouMean(owner, FormulationNames()) +
                       " (valid: " + Join(FormulationNames()) + ")");
  }
  const auto [key, value] = KeyValue(option, prefixed ? text.substr(colon + 1) : text);
  a->options[owner][key] = value;
}

StartKind ParseStart(const std::string& text) {
  return text == "cold" ? StartKind::kCold : StartKind::kWarm;
}

std::vector<std::string> Starts() { return {"warm", "cold"}; }
std::vector<std::string> RunStarts() { return {"warm", "cold", "near"}; }
std::vector<std::string> Modes() { return {"replay", "free"}; }
std::vector<std::string> BifurcationModes() { return {"off", "detect", "switch"}; }

// --- the table -------------------------------------------------------------------------------

constexpr unsigned kAll = kList | kRun | kCompare | kExport | kSchema | kPlot | kRerun;
constexpr unsigned kProblemCommands = kRun | kCompare | kExport;
constexpr unsigned kPathCommands = kRun | kCompare;

std::vector<Option> MakeOptions() {
  using A = RunArguments;
  using O = const Option&;
  using S = const std::string&;
  return {
      {"--problem", "NAME", kProblemCommands, Need::kProblem, false,
       "a named problem (`contactbench list` shows each one's parameters)", ProblemNames,
       [](O o, S v, A* a) { a->problem = Choice(o, v); }},
      {"--problem-file", "F.json", kProblemCommands, Need::kProblem, false,
       "a problem file: a truss, a plane-stress Q4 mesh, or an LCP (docs/problem-files.md)",
       nullptr, [](O, S v, A* a) { a->problem_file = v; }},
      {"--problem-dir", "DIR[,F...]", kCompare, Need::kProblem, false,
       "a problem set: every FCLIB file (.hdf5, .h5) of each directory listed, and each "
       "fixed-load problem file listed, solved by every formulation cold and from each of the "
       "file's guesses; records in problems.csv (docs/comparison.md, \"Problem sets\")",
       nullptr, [](O, S v, A* a) { a->problem_dir = v; }},
      {"--formulation", "NAME", kRun, Need::kRequired, false, "the formulation", FormulationNames,
       [](O o, S v, A* a) { a->formulation = Choice(o, v); }},
      {"--formulations", "A,B,...", kCompare, Need::kOptional, false,
       "the formulations compared (default: every one built)", FormulationNames,
       [](O o, S v, A* a) {
         a->formulations = NonEmptyList(o, v);
         for (const auto& f : a->formulations) Choice(o, f);
       }},
      {"--out", "DIR", kPathCommands | kRerun, Need::kRequired, false,
       "the directory of the records (created if missing; docs/records.md)", nullptr,
       [](O, S v, A* a) { a->out = v; }},
      {"--force", "", kRerun, Need::kOptional, false,
       "rerun even when the binary, a library, the BLAS, the process count or a copied input "
       "differs from what run.json records (each difference is printed)",
       nullptr, [](O, S, A* a) { a->force = true; }},
      {"--overwrite", "", kPathCommands | kRerun, Need::kOptional, false,
       "replace the records of an earlier run in --out (removes every record file and vtk/ "
       "first); without it such a directory is refused",
       nullptr, [](O, S, A* a) { a->overwrite = true; }},
      {"--out", "F.json", kExport, Need::kRequired, false, "the problem file to write", nullptr,
       [](O, S v, A* a) { a->out = v; }},
      {"--format", "json|fclib", kExport, Need::kOptional, false,
       "the problem file's format: the suite's JSON (default) or an FCLIB global problem, HDF5 "
       "with mu = 0 (docs/problem-files.md, \"FCLIB\")",
       nullptr,
       [](O o, S v, A* a) {
         if (v != "json" && v != "fclib") Refuse(o, "must be json or fclib, got '" + v + "'");
         a->export_format = v;
       }},
      {"--solver", "NAME", kPathCommands, Need::kOptional, false,
       "the equation solver of implicit-fb, nonsmooth-fb and active-set (default newton)",
       EquationSolverNames, [](O o, S v, A* a) { a->config.solver = Choice(o, v); }},
      {"--eta", "1|2|3|4", kPathCommands, Need::kOptional, false,
       "implicit-fb's eta case (docs/method.md section 2; default 1)", nullptr,
       [](O o, S v, A* a) {
         a->config.eta = ParseInteger(o, v);
         std::string why;
         if (!IsValidEtaCase(a->config.eta, &why)) Refuse(o, why);
       }},
      {"--steps", "N", kPathCommands, Need::kOptional, false,
       "accepted steps to take (default: the problem's)", nullptr,
       [](O o, S v, A* a) {
         a->steps = ParseInteger(o, v);
         if (*a->steps <= 0) Refuse(o, "must be a positive integer");
       }},
      {"--arc-length", "THETA", kPathCommands, Need::kOptional, false,
       "the arc length theta of (33) (default: the problem's)", nullptr,
       [](O o, S v, A* a) { a->arc_length = PositiveNumber(o, v); }},
      {"--start", "warm|cold|near|guess:K", kRun, Need::kOptional, false,
       "the start of each solve (default warm). near (fixed-load problems, e.g. P1): the solve "
       "starts from the solution of implicit-fb (eta 1, Newton) perturbed by the relative "
       "offset of --near-offset with a fixed pattern, as the report's section 5.1 starts eta "
       "case 3 near the solution. guess:K (an FCLIB file): from the file's /guesses/K",
       RunStarts,
       [](O o, S v, A* a) {
         if (v.rfind("guess:", 0) == 0) {
           a->start_guess = ParseInteger(o, v.substr(6));
           if (a->start_guess < 1) Refuse(o, "guess:K needs K >= 1, got '" + v + "'");
           return;
         }
         a->start_near = Choice(o, v) == "near";
         a->start = ParseStart(v);
       }},
      {"--near-offset", "DELTA", kRun, Need::kOptional, false,
       "the relative offset of --start near (default 1e-2)", nullptr,
       [](O o, S v, A* a) {
         a->near_offset = ParseNumber(o, v);
         if (!(a->near_offset >= 0.0)) Refuse(o, "must be >= 0");
       }},
      {"--starts", "warm,cold", kCompare, Need::kOptional, false,
       "the starts each formulation is run with (default warm)", Starts,
       [](O o, S v, A* a) {
         for (const auto& s : NonEmptyList(o, v)) a->starts.push_back(ParseStart(Choice(o, s)));
       }},
      {"--mode", "replay|free", kCompare, Need::kOptional, false,
       "replay (default): every formulation solves the reference path's steps, each from the "
       "reference's previous accepted state; free: each traces its own path",
       Modes, [](O o, S v, A* a) { a->mode = Choice(o, v); }},
      {"--reference", "NAME", kCompare, Need::kOptional, false,
       "the formulation that traces the reference path of replay mode (default implicit-fb)",
       FormulationNames, [](O o, S v, A* a) { a->reference = Choice(o, v); }},
      {"--tol", "T", kPathCommands, Need::kOptional, false,
       "the verdict's tolerance, in (0, 1e-4] (docs/method.md section 7; default 1e-8)", nullptr,
       [](O o, S v, A* a) { a->tolerance = VerdictTolerance(o, v); }},
      {"--linear-solver", "NAME", kPathCommands, Need::kOptional, false,
       "the sparse linear solver of the equation solvers", LinearSolverNames,
       [](O o, S v, A* a) { a->config.solver_options.linear_solver = Choice(o, v); }},
      {"--max-cutbacks", "N", kRun, Need::kOptional, false,
       "a step that fails is retried with theta halved at most N times (default 6)", nullptr,
       [](O o, S v, A* a) { a->max_cutbacks = NonNegativeInteger(o, v); }},
      {"--no-kinks", "", kRun, Need::kOptional, false,
       "do not locate the kinks (docs/method.md section 6)", nullptr,
       [](O, S, A* a) { a->locate_kinks = false; }},
      {"--bifurcations", "off|detect|switch", kRun, Need::kOptional, false,
       "detect (default): watch the sign of the bordered stiffness's determinant and record "
       "limit and bifurcation points in critical.csv; switch also locates the first "
       "bifurcation point and continues on the other branch",
       BifurcationModes,
       [](O o, S v, A* a) { ParseBifurcationMode(Choice(o, v), &a->bifurcations); }},
      {"--save-every", "N", kRun, Need::kOptional, false,
       "save the state every N accepted steps (default 0: only the critical points and the "
       "final state) in snapshots.csv, snapshot_contacts.csv and vtk/",
       nullptr, [](O o, S v, A* a) { a->save_every = NonNegativeInteger(o, v); }},
      {"--time-limit", "SECONDS", kPathCommands, Need::kOptional, false,
       "the time limit of each solve (default: none)", nullptr,
       [](O o, S v, A* a) { a->time_limit = PositiveNumber(o, v); }},
      {"--repeat", "N", kCompare, Need::kOptional, false,
       "solve every step N times from the same start (default 1): steps.csv records the first "
       "answer, judged by the verdict, with the median time of the N solves and their min and "
       "max; a repetition whose answer differs is flagged (repeats_agree, a warning)",
       nullptr,
       [](O o, S v, A* a) {
         a->repeat = ParseInteger(o, v);
         if (a->repeat <= 0) Refuse(o, "must be a positive integer, got '" + v + "'");
       }},
      {"--set", "KEY=VALUE", kProblemCommands, Need::kOptional, true,
       "change a problem parameter (`contactbench list` shows each problem's); a problem "
       "file's keys are length_scale, force_scale and load or arc_length, steps",
       nullptr,
       [](O o, S v, A* a) {
         const auto [key, value] = KeyValue(o, v);
         if (!a->settings.emplace(key, value).second) {
           Refuse(o, "the parameter '" + key + "' is given twice");
         }
       }},
      {"--allow-memory", "", kProblemCommands, Need::kOptional, false,
       "run a problem whose estimated memory exceeds what the machine has (MemAvailable, the "
       "memory cgroup's limit, RLIMIT_AS); without it such a problem is refused at once",
       nullptr, [](O, S, A* a) { a->allow_memory = true; }},
      {"--option", "KEY=VALUE", kRun, Need::kOptional, true,
       "a formulation's own setting (e.g. implicit-fb gamma_tol, rho_min); given as "
       "FORMULATION:KEY=VALUE, only for the formulation named",
       nullptr, [](O o, S v, A* a) { FormulationOption(o, v, false, a); }},
      {"--option", "FORMULATION:KEY=VALUE", kCompare, Need::kOptional, true,
       "a setting of the formulation named", nullptr,
       [](O o, S v, A* a) { FormulationOption(o, v, true, a); }},
      {"--plugin", "FILE", kPathCommands | kList, Need::kOptional, true,
       "load a plug-in's formulations (docs/your-own-method.md); read before the other options",
       nullptr, [](O, S, A*) {}},
      {"--petsc-options", "OPTIONS", kPathCommands, Need::kOptional, false,
       "PETSc options for the petsc-* formulations, over their defaults (a direct solve; "
       "docs/backend-petsc.md), e.g. \"-snes_monitor -snes_max_it 50\"; passed to PETSc as "
       "they are: an option naming a file (-options_file, -snes_monitor ascii:F, "
       "-snes_view_solution binary:F) reads or writes that path, anywhere the user can",
       nullptr, [](O, S v, A* a) { a->petsc_options = v; }},
      {"--step", "N", kExport, Need::kOptional, false,
       "with --format fclib, a path's step N (traced by implicit-fb) at its load, with its "
       "answer as /solution and step N - 1's state as /guesses/1",
       nullptr,
       [](O o, S v, A* a) {
         a->export_step = ParseInteger(o, v);
         if (*a->export_step <= 0) Refuse(o, "must be a positive integer");
       }},
      {"--step", "N", kPlot, Need::kOptional, false,
       "the step whose residual history is drawn (default: the one with the most iterations)",
       nullptr,
       [](O o, S v, A* a) {
         a->plot_step = ParseInteger(o, v);
         if (*a->plot_step <= 0) Refuse(o, "must be a positive integer");
       }},
      {"--figures", "DIR", kPlot, Need::kOptional, false,
       "where the figures go (default OUT_DIR/figures)", nullptr,
       [](O, S v, A* a) { a->figures = v; }},
      {"--help", "", kAll, Need::kOptional, false, "print this command's options and exit", nullptr,
       [](O, S, A* a) { a->help = true; }},
  };
}

bool Takes(const Option& option, Command command) { return (option.commands & command) != 0; }

const Option* FindOption(const std::string& name, Command command) {
  for (const Option& o : Options()) {
    if (o.name == name && Takes(o, command)) return &o;
  }
  return nullptr;
}

std::vector<std::string> OptionNames(Command command) {
  std::vector<std::string> names;
  for (const Option& o : Options()) {
    if (Takes(o, command) && !Contains(names, o.name)) names.push_back(o.name);
  }
  return names;
}

std::string ValidList(const Option& o) {
  return o.choices == nullptr ? "" : " (valid: " + Join(o.choices()) + ")";
}

// The problem is given by exactly one of its options; the required options are given.
void CheckNeeds(Command command, const std::set<std::string>& given, bool out_optional) {
  std::vector<std::string> problem_given, problem_forms;
  const Option* first_problem_option = nullptr;
  for (const Option& o : Options()) {
    if (!Takes(o, command) || o.need != Need::kProblem) continue;
    if (first_problem_option == nullptr) first_problem_option = &o;
    if (given.count(o.name)) problem_given.push_back(o.name);
    problem_forms.push_back(NameAndValue(o));
  }
  if (problem_given.size() > 1) {
    throw UsageError("give either " + Join(problem_given, " or ") + ", not both");
  }
  if (first_problem_option != nullptr && problem_given.empty()) {
    throw UsageError(Join(problem_forms, " or ") + " is required" +
                     ValidList(*first_problem_option));
  }
  for (const Option& o : Options()) {
    if (out_optional && std::string_view(o.name) == "--out") continue;
    if (Takes(o, command) && o.need == Need::kRequired && !given.count(o.name)) {
      throw UsageError(NameAndValue(o) + " is required" + ValidList(o));
    }
  }
}

// --- the text ------------------------------------------------------------------------------

constexpr std::size_t kWidth = 96;

// `words` filled into lines of at most kWidth columns; the first line continues a text of
// `used` columns, the others start with `indent` spaces. A word longer than a line stays whole.
std::string Fill(const std::vector<std::string>& words, std::size_t used, std::size_t indent) {
  std::string out;
  std::size_t column = used;
  bool line_start = true;
  for (const auto& word : words) {
    if (!line_start && column + 1 + word.size() > kWidth) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
      line_start = true;
    }
    if (!line_start) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    line_start = false;
  }
  return out;
}

std::vector<std::string> Words(const std::string& text) {
  std::vector<std::string> words;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t space = text.find(' ', start);
    const std::size_t end = space == std::string::npos ? text.size() : space;
    if (end > start) words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return words;
}

// The usage items of a command: the problem's options as one alternative, the required
// options, then the optional ones in brackets.
std::vector<std::string> UsageItems(Command command) {
  std::vector<std::string> problem, required, optional;
  for (const Option& o : Options()) {
    if (!Takes(o, command)) continue;
    const std::string item = NameAndValue(o) + (o.repeatable ? " ..." : "");
    if (o.need == Need::kProblem) problem.push_back(item);
    if (o.need == Need::kRequired) required.push_back(item);
    if (o.need == Need::kOptional) optional.push_back("[" + item + "]");
  }
  std::vector<std::string> items;
  for (const CommandInfo& c : Commands()) {
    if (c.command == command && c.operand != nullptr) items.emplace_back(c.operand);
  }
  if (problem.size() == 1) items.push_back(problem.front());
  if (problem.size() > 1)
    items.push_back(std::string("(").append(Join(problem, " | ")).append(")"));
  items.insert(items.end(), required.begin(), required.end());
  items.insert(items.end(), optional.begin(), optional.end());
  return items;
}

// `prefix` contactbench COMMAND ITEMS..., continued lines aligned under the first item.
std::string UsageLine(const CommandInfo& command, const std::string& prefix) {
  const std::string head = prefix + "contactbench " + command.name;
  return head + " " + Fill(UsageItems(command.command), head.size(), head.size() + 1) + "\n";
}

constexpr const char* kExitStatus =
    "Exit status: 0 every step verified; 2 bad arguments (or a bad problem file, a problem too "
    "large for the memory, or an output that cannot be written); 3 stopped on a failure (a "
    "step, a stagnating path, a write, out of memory; records kept); 4 interrupted by SIGINT or "
    "SIGTERM (records kept).";

// A problem set's solves are fixed-load, cold and from the files' guesses: the options of
// paths and of their starts would be ignored, so they are refused.
void RefuseForProblemSets(const std::set<std::string>& given) {
  for (const char* name : {"--starts", "--mode", "--reference", "--steps", "--arc-length"}) {
    if (given.count(name)) {
      throw UsageError(std::string(name) +
                       ": not with --problem-dir (its solves are fixed-load, cold and from "
                       "each file's guesses)");
    }
  }
}

void ApplyCompareDefaults(RunArguments* a) {
  if (a->formulations.empty()) {
    for (const auto& info : FormulationRegistry()) {
      if (info.available) a->formulations.push_back(info.name);
    }
  }
  if (a->starts.empty()) a->starts = {StartKind::kWarm};
}

}  // namespace

std::string NameAndValue(const Option& o) {
  return *o.placeholder == '\0' ? std::string(o.name) : std::string(o.name) + " " + o.placeholder;
}

std::string Join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : separator) + s;
  return out;
}

const std::vector<CommandInfo>& Commands() {
  static const std::vector<CommandInfo> commands = {
      {kList, "list",
       "Lists the problems with their parameters, the formulations and the solvers."},
      {kRun, "run",
       "Traces the problem's loading (the fixed-load solve, or the arc-length path) with one "
       "formulation and writes DIR/steps.csv, iterations.csv, kinks.csv, critical.csv, "
       "parameters.csv, solution.csv and contacts.csv (the final state), and the saved states "
       "(every --save-every N-th step, each critical point, the final state) in snapshots.csv, "
       "snapshot_contacts.csv, cells.csv and vtk/*.vtu, *.pvd. docs/records.md describes the "
       "columns."},
      {kCompare, "compare",
       "Every formulation x start traces the SAME steps (replay mode: each step starts from the "
       "reference path's previous accepted state; the reference is traced first by "
       "--reference) or its own path (free mode), into one long-format steps.csv and "
       "iterations.csv, the reference path's kinks.csv, and runs.csv (one row per formulation "
       "x start). A formulation that cannot express the problem's step constraint or refuses "
       "the problem is skipped, with the reason in runs.csv."},
      {kExport, "export",
       "Writes a named problem (or a problem file, normalised) as a problem file "
       "(docs/problem-files.md)."},
      {kSchema, "schema",
       "Prints the columns of every record file as markdown (the tables of docs/records.md)."},
      {kPlot, "plot",
       "Draws the figures of a run's or comparison's records (results/plot_run.py, with "
       "Debian's python3-matplotlib and python3-pandas): the path with its kinks and critical "
       "points, the deformed shapes with the obstacles, the iterations and time per step, a "
       "step's residual history and, for a comparison, the performance profiles and iteration "
       "histograms.",
       "OUT_DIR", "the --out directory of `contactbench run` or `contactbench compare`"},
      {kRerun, "rerun",
       "Runs the command DIR/run.json records again, into --out: the same options, with the "
       "copy of the problem file (and its meshes) kept in DIR/problem/. Refused, with each "
       "reason, when this binary, a linked library, the BLAS or the process count is not the "
       "recorded one, or a copy's SHA-256 is not the recorded one, unless --force. "
       "docs/records.md says which records a rerun reproduces.",
       "DIR", "the --out directory of the `contactbench run` or `compare` to rerun"},
  };
  return commands;
}

const CommandInfo* FindCommand(const std::string& name) {
  for (const CommandInfo& c : Commands()) {
    if (name == c.name) return &c;
  }
  return nullptr;
}

const std::vector<Option>& Options() {
  static const std::vector<Option> options = MakeOptions();
  return options;
}

RunArguments ParseArguments(Command command, const std::vector<std::string>& args,
                            bool out_optional) {
  const CommandInfo* info = nullptr;
  for (const CommandInfo& c : Commands()) {
    if (c.command == command) info = &c;
  }
  if (info == nullptr) throw std::logic_error("ParseArguments: a command without CommandInfo");
  const char* command_name = info->name;
  RunArguments a;
  std::set<std::string> given;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& name = args[i];
    if (info->operand != nullptr && (name.empty() || name[0] != '-')) {
      if (!a.operand.empty()) throw UsageError(std::string(info->operand) + " is given twice");
      a.operand = name;
      continue;
    }
    const Option* o = FindOption(name, command);
    if (o == nullptr) {
      throw UsageError(std::string(command_name) + ": unknown option '" + name + "'" +
                       DidYouMean(name, OptionNames(command)) +
                       " (valid: " + Join(OptionNames(command)) + ")");
    }
    const bool repeated = !given.insert(name).second;
    if (repeated && !o->repeatable) throw UsageError(name + " is given twice");
    const bool flag = *o->placeholder == '\0';
    if (!flag && i + 1 >= args.size()) throw UsageError(name + " needs a value");
    o->parse(*o, flag ? std::string() : args[++i], &a);
    if (a.help) return a;
  }
  CheckNeeds(command, given, out_optional);
  if (info->operand != nullptr && a.operand.empty()) {
    throw UsageError(std::string(info->operand) + " is required");
  }
  if (command == kCompare) ApplyCompareDefaults(&a);
  if (given.count("--problem-dir")) RefuseForProblemSets(given);
  return a;
}

std::string Synopsis(const CommandInfo& command) { return UsageLine(command, "usage: "); }

std::string UsageText() {
  std::string text = "usage:\n";
  for (const CommandInfo& c : Commands()) text += UsageLine(c, "  ");
  text += "  contactbench help\n  contactbench --version\n\n";
  text += Fill(Words("`contactbench COMMAND --help` says what a command does and what each of "
                     "its options means."),
               0, 0) +
          "\n";
  return text + Fill(Words(kExitStatus), 0, 0) + "\n";
}

std::string CommandHelp(const CommandInfo& command) {
  std::string text = Synopsis(command) + "\n";
  text += Fill(Words(std::string(command.summary)), 0, 0) + "\n\n";
  constexpr std::size_t kHelpColumn = 30;
  if (command.operand != nullptr) {
    std::string line = std::string("  ") + command.operand;
    line.resize(kHelpColumn, ' ');
    text += line + Fill(Words(command.operand_help), kHelpColumn, kHelpColumn) + "\n\n";
  }
  text += "options:\n";
  for (const Option& o : Options()) {
    if (!Takes(o, command.command)) continue;
    std::string line = "  " + NameAndValue(o);
    line += line.size() + 2 <= kHelpColumn ? std::string(kHelpColumn - line.size(), ' ')
                                           : "\n" + std::string(kHelpColumn, ' ');
    std::string help = o.help;
    if (o.choices != nullptr) help += "; one of: " + Join(o.choices());
    text += line + Fill(Words(help), kHelpColumn, kHelpColumn) + "\n";
  }
  // The exit statuses are those of the commands that load a problem.
  if ((command.command & (kRun | kCompare | kExport)) == 0) return text;
  return text + "\n" + Fill(Words(kExitStatus), 0, 0) + "\n";
}

}  // namespace cb::harness
