#include "harness/commands.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "formulations/registry.h"
#include "harness/cli.h"
#include "harness/compare_table.h"
#include "harness/interrupt.h"
#include "harness/memory_budget.h"
#include "harness/output_directory.h"
#include "harness/problem_set.h"
#include "harness/process_agreement.h"
#include "harness/records.h"
#include "harness/run_inputs.h"
#include "harness/snapshots.h"
#include "harness/suggest.h"
#include "io/problem_file.h"
#include "parallel/processes.h"
#include "path/near_start.h"
#include "path/path.h"
#include "path/replay.h"
#include "problems/problem_path.h"

namespace cb::harness {

// The configuration of formulation `name`: the common settings plus its own --option values.
FormulationConfig ConfigFor(const RunArguments& a, const std::string& name) {
  FormulationConfig config = a.config;
  for (const auto& owner : {std::string(), name}) {
    auto it = a.options.find(owner);
    if (it != a.options.end()) config.options.insert(it->second.begin(), it->second.end());
  }
  if (!a.petsc_options.empty() && TakesPetscOptions(name)) {
    config.options["petsc_options"] = a.petsc_options;
  }
  return config;
}

// The library's defaults for the problem (problem_path.h), changed by the options given.
PathOptions MakePathOptions(const RunArguments& a, const Problem& problem) {
  PathOptions options = DefaultPathOptions(problem);
  if (a.arc_length) options.arc_length = *a.arc_length;
  if (a.steps) options.max_steps = *a.steps;
  options.tolerance = a.tolerance;
  options.start = a.start;
  options.max_cutbacks = a.max_cutbacks;
  options.locate_kinks = a.locate_kinks;
  options.bifurcations = a.bifurcations;
  options.controls.time_limit_s = a.time_limit;
  // Agreed among the processes of a distributed run (process_agreement.h).
  options.controls.interrupted = [] { return InterruptedOnAnyProcess(); };
  return options;
}

void PrepareOutput(const std::string& dir) {
  std::error_code ec;
  // The root directory is nobody's output directory: --overwrite would remove /figures, /vtk.
  if (std::filesystem::weakly_canonical(dir, ec) == std::filesystem::path("/")) {
    throw InputError("--out: '" + dir + "' is the root directory; give a directory of its own");
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("--out: cannot create the directory '" + dir + "': " + ec.message());
  if (!std::filesystem::is_directory(dir, ec)) {
    throw InputError("--out: '" + dir + "' exists and is not a directory");
  }
  try {
    ProbeWritable(dir + "/.contactbench_write_test");
  } catch (const WriteError& e) {
    throw InputError("--out: the directory '" + dir + "' is not writable: " + e.what());
  }
}

namespace {

// The registry's entry of the run's formulation; null when it names none (refused later).
const FormulationInfo* InfoOf(const RunArguments& a) {
  const auto& formulations = FormulationRegistry();
  const auto info = std::find_if(formulations.begin(), formulations.end(),
                                 [&](const FormulationInfo& f) { return f.name == a.formulation; });
  return info == formulations.end() ? nullptr : &*info;
}

bool IsDistributed(const RunArguments& a) {
  const FormulationInfo* info = InfoOf(a);
  return info != nullptr && info->distributed;
}

// Whether the run factorises directly: every formulation but a distributed one given
// `linear=amg` (compare's formulations are taken as direct, the larger estimate).
bool FactorisesDirectly(const RunArguments& a) {
  if (!IsDistributed(a)) return true;
  for (const std::string& owner : {std::string(), a.formulation}) {
    const auto options = a.options.find(owner);
    if (options == a.options.end()) continue;
    const auto linear = options->second.find("linear");
    if (linear != options->second.end() && linear->second == "amg") return false;
  }
  return true;
}

// The memory of a model of `dofs` unknowns and `pairs` pairs in `dim` dimensions by the model
// of memory_budget.h: each pair acts on at most `dim` dofs (a node against an obstacle); in
// 3-D a direct factor fills by a top separator of `separator_nodes` nodes. The dense contact
// block is the serial condensed solve's (contact_block_factor.h): a distributed run keeps its
// contact rows in the sparse system.
MemoryEstimate EstimateOf(const RunArguments& a, double dofs, double pairs, int dim,
                          double separator_nodes) {
  const double contact_dofs = IsDistributed(a) ? 0.0 : std::min(dofs, dim * pairs);
  MemoryEstimate estimate{dofs, pairs, contact_dofs};
  if (!FactorisesDirectly(a)) {
    estimate.bytes_per_unknown = dim == 3 ? kBytesPerUnknownIterative3d : kBytesPerUnknownIterative;
  } else if (dim == 3) {
    estimate.fill = DirectFill3d(dofs, separator_nodes);
  }
  estimate.processes = LaunchedProcessCount();
  return estimate;
}

// An integer size of --set, or the named problem's default; nothing when the setting is not
// digits of at most 7 ("1e3" is no integer: the problem's own check refuses it, with its
// message).
std::optional<double> SizeSetting(const RunArguments& a, const std::string& name) {
  const auto set = a.settings.find(name);
  if (set == a.settings.end()) {
    for (const auto& info : ProblemRegistry()) {
      if (info.name == a.problem) return info.defaults().Integer(name);
    }
    return std::nullopt;
  }
  const std::string& text = set->second;
  if (text.empty() || text.size() > 7 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  return std::stod(text);
}

// The size of the named problems with a mesh, known before they are built: the block (P1,
// problems/block.cc), (n+1)^2 nodes of 2 dofs and 2(n+1) pairs on the wall and the floor; the
// 3-D boxes (problems/hertz.cc, plate.cc), (nx+1)(ny+1)(nz+1) nodes of 3 dofs and a bottom
// face of pairs, whose top separator is the two smaller sides. The other named problems are
// trusses too small to matter before they are built.
std::optional<MemoryEstimate> PredictedEstimate(const RunArguments& a) {
  if (!a.problem_file.empty()) return std::nullopt;
  if (a.problem == "block") {
    if (!a.settings.contains("n")) return std::nullopt;  // the default, 50, is small
    const auto n = SizeSetting(a, "n");
    if (!n) return std::nullopt;
    return EstimateOf(a, 2.0 * (*n + 1.0) * (*n + 1.0), 2.0 * (*n + 1.0), 2, 0.0);
  }
  const bool hertz = a.problem == "hertz-3d";
  if (!hertz && a.problem != "plate-3d") return std::nullopt;
  const auto nx = SizeSetting(a, hertz ? "n" : "nx");
  const auto ny = SizeSetting(a, hertz ? "n" : "ny");
  const auto nz = SizeSetting(a, "nz");
  if (!nx || !ny || !nz) return std::nullopt;
  std::array<double, 3> nodes{*nx + 1.0, *ny + 1.0, *nz + 1.0};
  std::sort(nodes.begin(), nodes.end());
  return EstimateOf(a, 3.0 * nodes[0] * nodes[1] * nodes[2], (*nx + 1.0) * (*ny + 1.0), 3,
                    nodes[0] * nodes[1]);
}

// The estimate of a built problem: a body's dimension and nodes; a 3-D mesh's separator taken
// as a cube's, N^(2/3) of its N nodes, unless the box's own was predicted.
MemoryEstimate BuiltEstimate(const RunArguments& a, const Problem& problem) {
  const double dofs = problem.model->num_dofs(), pairs = problem.model->num_pairs();
  const int dim = problem.body ? problem.body->body().dim() : 2;
  if (const auto predicted = PredictedEstimate(a); predicted && dim == 3) {
    const double separator = std::pow(predicted->fill / std::max(predicted->dofs, 1.0), 2.0);
    return EstimateOf(a, dofs, pairs, dim, separator);
  }
  const double nodes = problem.body ? problem.body->body().num_nodes() : dofs;
  return EstimateOf(a, dofs, pairs, dim, std::pow(nodes, 2.0 / 3.0));
}

// The parameters --set may change: a named problem's declared ones, a problem file's as
// loading it without settings gives them. Empty when there is no such problem.
std::vector<std::string> SettableParameters(const RunArguments& a) {
  std::vector<std::string> names;
  try {
    Parameters declared;
    if (!a.problem_file.empty()) {
      declared = io::LoadProblemFile(a.problem_file).parameters;
    } else {
      for (const auto& info : ProblemRegistry()) {
        if (info.name == a.problem) declared = info.defaults();
      }
    }
    for (const auto& entry : declared.entries()) names.push_back(entry.name);
  } catch (const std::exception&) {
    names.clear();  // the file itself is refused: the refusal was not about a setting
  }
  return names;
}

// "; did you mean 'X'?" for the first --set key the problem does not declare, or "". Asked
// only after the problem was refused.
std::string SettingSuggestion(const RunArguments& a) {
  const std::vector<std::string> known = SettableParameters(a);
  if (known.empty()) return "";
  for (const auto& setting : a.settings) {
    if (std::find(known.begin(), known.end(), setting.first) == known.end()) {
      return DidYouMean(setting.first, known);
    }
  }
  return "";
}

// A formulation's refusal of its settings, with the closest known key for an unknown one.
[[noreturn]] void RefuseFormulationSettings(const std::invalid_argument& e) {
  const auto* unknown = dynamic_cast<const UnknownOptionError*>(&e);
  throw UsageError(e.what() + (unknown ? DidYouMean(unknown->key(), unknown->known()) : ""));
}

}  // namespace

Problem LoadProblem(const RunArguments& a) {
  const std::string what =
      a.problem_file.empty() ? "--problem " + a.problem : "--problem-file " + a.problem_file;
  if (const auto predicted = PredictedEstimate(a)) CheckMemory(*predicted, what, a.allow_memory);
  const Activity building("building the problem");
  Problem problem;
  try {
    // --allow-memory lifts the bound on a problem file's size too (io/input_bounds.h).
    problem = !a.problem_file.empty()
                  ? io::LoadProblemFile(a.problem_file, a.settings,
                                        a.allow_memory ? 0 : io::kProblemFileMaxBytes)
                  : MakeProblem(a.problem, a.settings);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what() + SettingSuggestion(a));
  }
  CheckMemory(BuiltEstimate(a, problem), what, a.allow_memory);
  return problem;
}

namespace {

// What run.json records of the arguments, before anything runs.
void DescribeArguments(const RunArguments& a, const Problem& problem, RunJson* record) {
  record->problem = problem.name;
  record->problem_source =
      a.problem_file.empty() ? "--problem " + a.problem : "--problem-file " + a.problem_file;
  record->problem_notes = problem.notes;
  record->control = problem.control_label;
  record->settings = a.settings;
  record->tolerance = a.tolerance;
  record->time_limit_s = a.time_limit;
}

// Runs `body` in the output directory of --out, prepared, locked against a second run and
// claimed (an earlier run's records refused, or removed with --overwrite), and ends with
// run.json whatever ends the command: a status, a failure or a failed write (rethrown for the
// message). `body` returns the exit status and sets the reason.
int InOutputDirectory(const RunArguments& a, RunJson* record,
                      const std::function<int(const RecordTarget&, std::string* reason)>& body) {
  PrepareOutput(a.out);
  const OutputLock lock(a.out);
  ClaimOutput(a.out, a.overwrite);
  std::string reason;
  int status = kExitFailure;
  try {
    if (!a.problem_file.empty()) record->inputs = CopyProblemInputs(a.problem_file, a.out);
    status = body(RecordTarget(a.out), &reason);
  } catch (const UsageError& e) {
    WriteRunJson(a.out, *record, kExitBadArguments, e.what());
    throw;
  } catch (const Interrupted& e) {
    WriteRunJson(a.out, *record, kExitInterrupted, e.what());
    throw;
  } catch (const std::bad_alloc&) {
    WriteRunJson(a.out, *record, kExitFailure,
                 std::string("out of memory while ") + Activity::Current());
    throw;
  } catch (const std::exception& e) {
    WriteRunJson(a.out, *record, kExitFailure, e.what());
    throw;
  }
  WriteRunJson(a.out, *record, status, reason);
  return status;
}

// Runs `body` with the records in `memory` (no output directory), run.json's text among them.
int InMemory(const RunArguments& a, RunJson* record, RecordTexts* memory,
             const std::function<int(const RecordTarget&, std::string* reason)>& body) {
  if (!a.out.empty()) throw std::logic_error("records in memory and in --out both");
  if (a.save_every > 0) throw UsageError("--save-every: the saved states need an output directory");
  if (Distributed()) throw UsageError("records in memory: not in a run of several processes");
  memory->clear();
  std::string reason;
  const int status = body(RecordTarget(memory), &reason);
  (*memory)["run.json"] = RunJsonText(*record, status, reason);
  return status;
}

}  // namespace

int WithRecords(const RunArguments& a, RunJson* record, RecordTexts* memory,
                const std::function<int(const RecordTarget&, std::string* reason)>& body) {
  return memory != nullptr ? InMemory(a, record, memory, body) : InOutputDirectory(a, record, body);
}

namespace {

// Where the records went, for the messages.
std::string Destination(const RecordTarget& target) {
  return target.memory != nullptr ? "memory" : target.directory;
}

// What the summary line of a run counts: for a fixed-load solve (P1, an LCP) the iterations and
// the time it took, for a path its steps and what was found along it.
std::string SummaryCounts(const Problem& problem, const PathSummary& summary,
                          const RunRecorder& recorder) {
  char text[256];
  if (problem.loading == LoadingKind::kFixedLoad) {
    int iterations = 0;
    for (int n : recorder.iterations()) iterations += n;
    double time_s = 0.0;
    for (double t : recorder.solve_times_s()) time_s += t;
    std::snprintf(text, sizeof text, "%d iterations, %.3g s", iterations, time_s);
  } else {
    std::snprintf(text, sizeof text,
                  "%d accepted steps, %d attempts, %d kinks, %d limit points, "
                  "%d bifurcation points, %d branch switches",
                  summary.accepted_steps, summary.attempts, summary.kinks, summary.limit_points,
                  summary.bifurcations, summary.branch_switches);
  }
  return text;
}

// "<problem> <formulation>: <what happened> (<counts>) -> <where>", the counts once: a path
// traced to its end says so in the counts alone; then, for records on disk, the command that
// draws them.
void PrintSummaryLine(const Problem& problem, const Formulation& formulation,
                      const PathSummary& summary, const RunRecorder& recorder,
                      const RecordTarget& target) {
  const std::string counts = SummaryCounts(problem, summary, recorder);
  const bool only_counts =
      summary.status == Status::kConverged &&
      summary.message == std::to_string(summary.accepted_steps) + " steps accepted";
  const std::string what =
      only_counts ? "path traced: " + counts : summary.message + " (" + counts + ")";
  std::fprintf(stderr, "%s %s: %s -> %s\n", problem.name.c_str(), formulation.name().c_str(),
               what.c_str(), Destination(target).c_str());
  if (target.memory == nullptr) {
    std::fprintf(stderr, "plot: contactbench plot %s\n", target.directory.c_str());
  }
}

// The start a run's records name: warm, cold, near or guess:K.
std::string StartLabel(const RunArguments& a) {
  if (a.start_guess > 0) return "guess:" + std::to_string(a.start_guess);
  return a.start_near ? "near" : ToString(a.start);
}

// The run itself, its records in `target` (a claimed output directory or memory). `guess`:
// --start guess:K's state, the start of the fixed-load solve.
struct TracedRun {  // what TraceRun traces: the problem, the formulation and their settings
  const Problem& problem;
  Formulation& formulation;
  const PathOptions& options;
  const ElementSplit& split;  // the formulation's split of the body over the processes
};

int TraceRun(const RunArguments& a, const TracedRun& run, const RecordTarget& target,
             OutputReadyWord* ready, RunJson* record, std::string* reason,
             std::optional<State> near) {
  const Problem& problem = run.problem;
  Formulation& formulation = run.formulation;
  const PathOptions& options = run.options;
  // --start near: the reference formulation's solution, perturbed (near_start.h).
  if (a.start_near) {
    auto reference = MakeFormulation("implicit-fb", FormulationConfig());
    const Activity solving("solving --start near's reference problem");
    std::string why;
    near.emplace();
    if (!NearSolutionStart(*problem.model, problem.scales, ZeroState(*problem.model), problem.load,
                           *reference, options, a.near_offset, &*near, &why)) {
      const bool interrupted = InterruptRequested();
      *reason = interrupted ? "interrupted during --start near's reference solve (" + why + ")"
                            : "--start near: the reference solve failed (" + why + ")";
      std::fprintf(stderr, "contactbench: %s\n", reason->c_str());
      return interrupted ? kExitInterrupted : kExitFailure;
    }
  }
  RecordFiles files(target);
  RunRecorder recorder(&files, problem,
                       {problem.name, formulation.name(), formulation.solver(),
                        formulation.settings(), StartLabel(a), "run"},
                       problem.loading == LoadingKind::kFixedLoad ? 1 : options.max_steps);
  WriteParameters(target, problem);
  // The saved states are files (VTK among them): only in an output directory.
  std::optional<SnapshotWriter> snapshots;
  if (target.memory == nullptr) snapshots.emplace(a.out, problem, a.save_every, &run.split);
  ready->Ready(a.out + "/vtk");     // the other processes of a distributed run may write there now
  AgreedRecords agreed(&recorder);  // with the other processes of a distributed run
  std::vector<PathObserver*> watching{&agreed};
  if (snapshots) watching.push_back(&*snapshots);
  ObserverTee observers(watching);
  // Whatever ends the path (a failure on another process of a distributed run among them),
  // run.json counts the records written (issue 30: counts of 0 beside 66-92 rows of steps.csv).
  record->runs = 1;
  const auto count_records = [&] {
    record->attempts = recorder.attempts();
    record->accepted_steps = recorder.accepted();
  };
  PathSummary summary;
  try {
    const Activity solving("solving");
    summary = TraceProblem(problem, formulation, options, &observers, near ? &*near : nullptr);
    if (summary.status == Status::kStoppedByCaller) AcknowledgeInterrupt();
    const Activity writing("writing the final state");
    // The snapshot first: in a distributed run the last step all processes take together.
    if (snapshots) snapshots->Save(summary.final_state, summary.accepted_steps, "final");
    OnEveryProcess("writing the final state", [&] {
      WriteFinalState(target, problem, summary.final_state, summary.accepted_steps);
    });
  } catch (...) {
    count_records();
    throw;
  }
  record->attempts = summary.attempts;
  record->accepted_steps = summary.accepted_steps;
  record->kinks = summary.kinks;
  *reason = summary.message;
  recorder.EndProgress();
  PrintSummaryLine(problem, formulation, summary, recorder, target);
  if (summary.status == Status::kStoppedByCaller) return kExitInterrupted;
  if (summary.status != Status::kConverged) return kExitFailure;
  return kExitOk;
}

// A distributed run's processes other than 0 (petsc_dist.h): the same path, every decision
// taken on values all processes share, and only their pieces of the saved states written, in
// the directory process 0 has made ready (a failure there ends them quietly: process 0 says why).
int FollowRun(const RunArguments& a, const TracedRun& run) {
  if (const int refused = AwaitOutputReady(a.out + "/vtk"); refused != 0) return refused;
  const Problem& problem = run.problem;
  SnapshotWriter pieces(a.out, problem, a.save_every, &run.split);
  AgreedRecords agreed(nullptr);  // process 0's record writes, agreed (process_agreement.h)
  ObserverTee observers({&agreed, &pieces});
  const PathSummary summary = TraceProblem(problem, run.formulation, run.options, &observers);
  if (summary.status == Status::kStoppedByCaller) AcknowledgeInterrupt();  // as process 0 does
  pieces.Save(summary.final_state, summary.accepted_steps, "final");
  OnEveryProcess("writing the final state", [] {});  // process 0 writes it
  if (summary.status == Status::kStoppedByCaller) return kExitInterrupted;
  return summary.status == Status::kConverged ? kExitOk : kExitFailure;
}

// The formulation of `run`, made with its settings (refused as bad arguments); a distributed
// one records its split of the body in `split`, which outlives it.
std::unique_ptr<Formulation> MakeRunFormulation(const RunArguments& a,
                                                ElementSplit* split = nullptr) {
  if (!a.petsc_options.empty() && !TakesPetscOptions(a.formulation)) {
    throw UsageError("--petsc-options: " + a.formulation + " is not a PETSc formulation");
  }
  FormulationConfig config = ConfigFor(a, a.formulation);
  config.element_split = split;
  try {
    return MakeFormulation(a.formulation, config);
  } catch (const std::invalid_argument& e) {
    RefuseFormulationSettings(e);
  }
}

}  // namespace

std::unique_ptr<Formulation> MakeConfiguredFormulation(const RunArguments& a,
                                                       const std::string& name) {
  try {
    return MakeFormulation(name, ConfigFor(a, name));
  } catch (const std::invalid_argument& e) {
    RefuseFormulationSettings(e);
  }
}

bool AcceptsProblem(const RunArguments& a, std::string* reason) {
  const Problem problem = LoadProblem(a);
  return MakeRunFormulation(a)->Accepts(FirstStep(problem, MakePathOptions(a, problem)), reason);
}

int RunCommand(const RunArguments& a, RunJson* record, RecordTexts* memory) {
  Problem problem = LoadProblem(a);
  ElementSplit split;  // the run's: the formulation records, the writers read
  std::unique_ptr<Formulation> formulation = MakeRunFormulation(a, &split);
  const PathOptions options = MakePathOptions(a, problem);
  const TracedRun run{problem, *formulation, options, split};
  std::string refusal;
  if (!formulation->Accepts(FirstStep(problem, options), &refusal)) {
    throw InputError(refusal + " (problem '" + problem.name + "')");
  }
  if (a.start_near && problem.loading != LoadingKind::kFixedLoad) {
    throw UsageError("--start near: only for fixed-load problems; '" + problem.name +
                     "' is traced by arc length");
  }
  if (a.start_near && Distributed()) {
    throw UsageError("--start near: not in a run of several processes");
  }
  const std::optional<State> guess = GuessStart(a, problem);
  if (guess && Distributed()) {
    throw UsageError("--start guess:K: not in a run of several processes");
  }
  if (ProcessRank() != 0) return FollowRun(a, run);
  OutputReadyWord ready;  // to the other processes, even when this one fails before
  DescribeArguments(a, problem, record);
  record->formulations = {formulation->name()};
  record->starts = {StartLabel(a)};
  try {
    return WithRecords(a, record, memory, [&](const RecordTarget& target, std::string* reason) {
      return TraceRun(a, run, target, &ready, record, reason, guess);
    });
  } catch (const UsageError&) {
    ready.Refused(kExitBadArguments);  // a refused --out: status 2 on every process
    throw;
  }
}

namespace {

// The comparison itself, its records in `target` (a claimed output directory or memory).
// Says on standard error that some solves of a run gave another answer when repeated: their
// times are not those of one solve (the first answer is still the one judged and recorded).
void WarnOfDisagreements(const RunLabel& label, const RunRecorder& recorder) {
  if (recorder.repeat_disagreements() == 0) return;
  std::fprintf(stderr,
               "warning: %s %s: %d solves gave another answer when repeated (first: %s); the "
               "first answer is judged, repeats_agree = false in steps.csv\n",
               label.formulation.c_str(), label.start.c_str(), recorder.repeat_disagreements(),
               recorder.first_disagreement().c_str());
}

// What every run of a comparison shares: the arguments, the problem, the path options, the
// reference path (replay mode), and where the records and the summary table go.
struct Comparison {
  const RunArguments& a;
  const Problem& problem;
  const StepProblem& first;
  const PathOptions& options;
  const PathRecorder& path;
  int total;
  RecordFiles* files;
  RecordWriter<RunOutcomeRow>* runs;
  std::vector<CompareTableRow>* table;
  RunJson* record;
};

// The reference path: the work every formulation is given in replay mode (warm start,
// cut-backs and kinks as in `run`). Its kinks are the ones recorded. False, with the reason,
// when it has no verified step to replay.
bool TraceReference(const Problem& problem, Formulation* reference, int total,
                    const PathOptions& options, RecordFiles* files, PathRecorder* path,
                    std::string* reason) {
  RunRecorder kinks_only(files, problem,
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
  tee.path = path;
  tee.kinks = &kinks_only;
  const PathSummary s = TraceProblem(problem, *reference, options, &tee);
  std::fprintf(stderr, "reference %s: %s\n", reference->name().c_str(), s.message.c_str());
  if (path->steps.empty()) {
    *reason = "the reference path has no verified step to replay (" + s.message + ")";
    std::fprintf(stderr, "contactbench: %s\n", reason->c_str());
    return false;
  }
  return true;
}

// One formulation from one start: skipped when it does not accept the first step, else the
// reference path replayed (or the problem traced); its outcome in runs.csv, the table and the
// run record. False, with the reason, when the caller stopped it.
bool CompareOne(const Comparison& c, Formulation& formulation, StartKind start,
                std::string* reason) {
  const RunArguments& a = c.a;
  const Problem& problem = c.problem;
  const RunLabel label{problem.name,           formulation.name(), formulation.solver(),
                       formulation.settings(), ToString(start),    a.mode};
  std::string why;
  if (!formulation.Accepts(c.first, &why)) {
    std::fprintf(stderr, "skipping %s: %s\n", formulation.name().c_str(), why.c_str());
    c.runs->Write({label, "skipped", 0, 0, why, a.time_limit, a.tolerance});
    c.table->push_back({formulation.name(), ToString(start), "skipped", {}, {}});
    return true;
  }
  RunRecorder recorder(c.files, problem, label,
                       a.mode == "replay" ? static_cast<int>(c.path.steps.size()) : c.total);
  PathOptions run_options = c.options;
  run_options.start = start;
  run_options.locate_kinks = false;  // the reference path's kinks are the recorded ones
  run_options.solve_repeats = a.repeat;
  const PathSummary s = a.mode == "replay"
                            ? ReplayPath(*problem.model, problem.scales, ZeroState(*problem.model),
                                         c.path, formulation, run_options, &recorder)
                            : TraceProblem(problem, formulation, run_options, &recorder);
  recorder.EndProgress();
  c.runs->Write({label, ToString(s.status), recorder.attempts(), recorder.accepted(), s.message,
                 a.time_limit, a.tolerance});
  c.table->push_back(
      {formulation.name(), ToString(start),
       std::to_string(recorder.accepted()) + "/" + std::to_string(recorder.total_steps()),
       recorder.iterations(), recorder.solve_times_s(), recorder.fastest_solve_s(),
       recorder.slowest_solve_s()});
  WarnOfDisagreements(label, recorder);
  RunJson* record = c.record;
  ++record->runs;
  record->repeat_disagreements += recorder.repeat_disagreements();
  record->attempts += recorder.attempts();
  record->accepted_steps += recorder.accepted();
  if (s.status == Status::kStoppedByCaller) {
    *reason = formulation.name() + ": " + s.message;
    return false;
  }
  return true;
}

int CompareRuns(const RunArguments& a, const Problem& problem,
                const std::vector<std::unique_ptr<Formulation>>& formulations,
                Formulation* reference, const RecordTarget& target, RunJson* record,
                std::string* reason) {
  PathOptions options = MakePathOptions(a, problem);
  const StepProblem first = FirstStep(problem, options);
  const int total = problem.loading == LoadingKind::kFixedLoad ? 1 : options.max_steps;
  RecordFiles files(target);
  RecordWriter<RunOutcomeRow> runs(target, RunsSchema());
  const Activity comparing("comparing the formulations");
  PathRecorder path;
  if (a.mode == "replay") {
    options.start = StartKind::kWarm;
    if (!TraceReference(problem, reference, total, options, &files, &path, reason)) {
      return kExitFailure;
    }
  }
  std::vector<CompareTableRow> table;
  const Comparison comparison{a,     problem, first, options, path,
                              total, &files,  &runs, &table,  record};
  for (const auto& formulation : formulations) {
    for (StartKind start : a.starts) {
      if (!CompareOne(comparison, *formulation, start, reason)) return kExitInterrupted;
    }
  }
  *reason = "every formulation was run (runs.csv holds each one's outcome)";
  if (record->repeat_disagreements > 0) {
    *reason += "; " + std::to_string(record->repeat_disagreements) +
               " solves' repetitions disagreed with their first answer (repeats_agree in "
               "steps.csv)";
  }
  std::fprintf(stderr, "%scompare: records in %s\n", CompareTable(table).c_str(),
               Destination(target).c_str());
  return kExitOk;
}

}  // namespace

int CompareCommand(const RunArguments& a, RunJson* record, RecordTexts* memory) {
  if (!a.problem_dir.empty()) return ProblemSetCommand(a, record, memory);
  Problem problem = LoadProblem(a);
  std::vector<std::unique_ptr<Formulation>> formulations;
  std::unique_ptr<Formulation> reference;
  try {
    for (const auto& name : a.formulations) {
      formulations.push_back(MakeFormulation(name, ConfigFor(a, name)));
    }
    reference = MakeFormulation(a.reference, ConfigFor(a, a.reference));
  } catch (const std::invalid_argument& e) {
    RefuseFormulationSettings(e);
  }
  if (Distributed()) throw UsageError("compare: runs in one process only (not mpirun)");
  // The reference traces the path every formulation replays: one that cannot take the
  // problem's steps is a bad argument, refused before any work.
  std::string refusal;
  if (a.mode == "replay" &&
      !reference->Accepts(FirstStep(problem, MakePathOptions(a, problem)), &refusal)) {
    throw UsageError("--reference " + reference->name() + ": " + refusal + " (problem '" +
                     problem.name + "')");
  }
  DescribeArguments(a, problem, record);
  for (const auto& f : formulations) record->formulations.push_back(f->name());
  for (StartKind start : a.starts) record->starts.push_back(ToString(start));
  record->mode = a.mode;
  record->repeat = a.repeat;
  if (a.mode == "replay") record->reference = reference->name();
  return WithRecords(a, record, memory, [&](const RecordTarget& target, std::string* reason) {
    return CompareRuns(a, problem, formulations, reference.get(), target, record, reason);
  });
}

}  // namespace cb::harness
