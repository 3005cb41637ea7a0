// The option table of contactbench and its command table: what each command takes, with the
// help text and the parser of each value. Tables, read as tables: MakeOptions is one entry per
// option and longer than a function of steps would be.
#include <set>

#include "formulations/implicit_fb/eta_equation.h"
#include "formulations/registry.h"
#include "harness/option_values.h"
#include "harness/options.h"
#include "problems/problem.h"
#include "solvers/equation_solver.h"
#include "solvers/linear_solver.h"

namespace cb::harness {

namespace {

using namespace option_values;  // NOLINT(google-build-using-namespace): the table's parsers

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
       "a formulation's own setting (e.g. implicit-fb gamma_tol, rho_min, reduced_newton=0: "
       "Newton on all the unknowns, not the contact unknowns alone, docs/method.md); given as "
       "FORMULATION:KEY=VALUE, "
       "only for the formulation named",
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

}  // namespace

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

}  // namespace cb::harness
