#include "harness/problem_set.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "formulations/registry.h"
#include "harness/cli.h"
#include "harness/compare_table.h"
#include "harness/interrupt.h"
#include "harness/memory_budget.h"
#include "harness/records.h"
#include "io/fclib_file.h"
#include "parallel/processes.h"
#include "path/path.h"
#include "problems/problem_path.h"
#include "verdict/natural_map_error.h"

namespace cb::harness {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> SplitItems(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    if (comma > start) items.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

// A file a directory of a set contributes: an FCLIB file or a JSON problem file (a Gmsh mesh
// is no problem file; the JSON file that names it is).
bool IsSetFile(const fs::path& path) {
  return io::IsFclibPath(path.string()) || path.extension() == ".json";
}

// A directory's problem files, sorted by name so that the records come in the same order on
// every machine.
std::vector<std::string> ProblemFilesIn(const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && IsSetFile(entry.path())) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    throw InputError("--problem-dir: '" + dir +
                     "' holds no problem file (FCLIB .hdf5, .h5, or JSON .json)");
  }
  return files;
}

// The run's arguments for one file of the set: --problem-file F with the set's --set, but for
// `friction`, which only FCLIB files have (a set may mix frictional FCLIB files, which need
// friction=ignore, with JSON files, which would refuse the unknown setting).
RunArguments FileArguments(const RunArguments& a, const std::string& file) {
  RunArguments one = a;
  one.problem_dir.clear();
  one.problem_file = file;
  if (!io::IsFclibPath(file)) one.settings.erase("friction");
  return one;
}

// Fixed-load solves only: a problem traced by arc length has no single answer to compare.
Problem LoadSetProblem(const RunArguments& a, const std::string& file) {
  Problem problem = LoadProblem(FileArguments(a, file));
  if (problem.loading != LoadingKind::kFixedLoad) {
    throw InputError("--problem-dir: " + file +
                     ": traced by arc length; a problem set takes fixed-load problems");
  }
  return problem;
}

PathOptions SetPathOptions(const RunArguments& a, const Problem& problem, const State* guess) {
  PathOptions options = DefaultPathOptions(problem);
  options.tolerance = a.tolerance;
  // Cold: the formulation's fixed start; a guess is a warm start from it (SolveFixedLoad).
  options.start = guess != nullptr ? StartKind::kWarm : StartKind::kCold;
  options.controls.time_limit_s = a.time_limit;
  options.controls.interrupted = [] { return InterruptRequested(); };
  options.solve_repeats = a.repeat;
  return options;
}

// The starts of a problem: cold, then each of the file's guesses (FCLIB files only).
struct SetStart {
  std::string label;
  std::optional<State> guess;
};

std::vector<SetStart> StartsOf(const std::string& file, const Problem& problem) {
  std::vector<SetStart> starts{{"cold", std::nullopt}};
  if (!io::IsFclibPath(file)) return starts;
  const io::FclibAnswers answers = io::LoadFclibAnswers(file);
  for (std::size_t k = 0; k < answers.guesses.size(); ++k) {
    State guess = ZeroState(*problem.model);
    guess.u = answers.guesses[k].u;
    guess.r = answers.guesses[k].r;
    starts.push_back({"guess:" + std::to_string(k + 1), guess});
  }
  return starts;
}

// Forwards to the run's recorder and keeps the solve's attempt for problems.csv.
struct LastAttempt final : PathObserver {
  explicit LastAttempt(RunRecorder* recorder) : recorder(recorder) {}
  void OnAttempt(const StepAttempt& attempt) override {
    recorder->OnAttempt(attempt);
    last = attempt;
  }
  RunRecorder* recorder;
  std::optional<StepAttempt> last;
};

// What the set's files and runs write, and the counts of run.json.
struct SetOutput {
  const RunArguments& a;
  RecordFiles files;
  RecordWriter<ProblemSetRow> rows;
  std::vector<CompareTableRow> table;
  RunJson* record;
};

// One formulation x start on one problem; false when the solve was interrupted.
bool SolveOne(const std::string& file, const Problem& problem, Formulation& formulation,
              const SetStart& start, SetOutput* out) {
  const RunArguments& a = out->a;
  const State* guess = start.guess ? &*start.guess : nullptr;
  const PathOptions options = SetPathOptions(a, problem, guess);
  const StepProblem step = FirstStep(problem, options);
  const RunLabel label{problem.name,           formulation.name(), formulation.solver(),
                       formulation.settings(), start.label,        "set"};
  const std::string table_name = problem.name + " " + formulation.name();
  std::string why;
  if (!formulation.Accepts(step, &why)) {
    out->rows.Write({label, file, &problem, nullptr, std::nan(""), why, a.time_limit, a.tolerance});
    out->table.push_back({table_name, start.label, "skipped", {}, {}});
    return true;
  }
  RunRecorder recorder(&out->files, problem, label, 1);
  LastAttempt observer(&recorder);
  const PathSummary s = TraceProblem(problem, formulation, options, &observer, guess);
  recorder.EndProgress();
  if (s.status == Status::kStoppedByCaller) return false;
  if (!observer.last) throw std::logic_error("a fixed-load solve without an attempt");
  const StepAttempt& attempt = *observer.last;
  out->rows.Write({label, file, &problem, &attempt, NaturalMapError(step, attempt.result.point),
                   attempt.result.message, a.time_limit, a.tolerance});
  out->table.push_back({table_name, start.label, std::to_string(recorder.accepted()) + "/1",
                        recorder.iterations(), recorder.solve_times_s(), recorder.fastest_solve_s(),
                        recorder.slowest_solve_s()});
  ++out->record->runs;
  out->record->attempts += recorder.attempts();
  out->record->accepted_steps += recorder.accepted();
  out->record->repeat_disagreements += recorder.repeat_disagreements();
  return true;
}

std::vector<std::unique_ptr<Formulation>> MakeFormulations(const RunArguments& a) {
  std::vector<std::unique_ptr<Formulation>> formulations;
  for (const auto& name : a.formulations)
    formulations.push_back(MakeConfiguredFormulation(a, name));
  return formulations;
}

// Every file loaded once before any work, its guesses too: why each cannot be read ("" when it
// can), so that a bad file is a row of problems.csv and not the end of the set. A second
// problem of the same name cannot be read either (the records tell problems apart by name).
// The notes of each go to run.json, prefixed with its problem's name. Throws InputError when no
// file can be read: nothing would be run.
std::vector<std::string> CheckFiles(const RunArguments& a, const std::vector<std::string>& files,
                                    RunJson* record) {
  std::vector<std::string> reasons;
  std::set<std::string> names;
  for (const auto& file : files) {
    try {
      const Problem problem = LoadSetProblem(a, file);
      StartsOf(file, problem);
      if (!names.insert(problem.name).second) {
        throw InputError("a second problem named '" + problem.name +
                         "' (the records tell problems apart by name)");
      }
      for (const auto& note : problem.notes)
        record->problem_notes.push_back(problem.name + ": " + note);
      reasons.emplace_back();
    } catch (const std::invalid_argument& e) {  // io::InputError: the file's own refusal
      reasons.emplace_back(e.what());
    } catch (const InputError& e) {  // LoadProblem's, with a --set suggestion
      reasons.emplace_back(e.what());
    }
  }
  if (std::all_of(reasons.begin(), reasons.end(), [](const auto& r) { return !r.empty(); })) {
    throw InputError(files.size() == 1 ? reasons.front()
                                       : "--problem-dir: no file could be read; " + files.front() +
                                             ": " + reasons.front());
  }
  return reasons;
}

// A file that could not be read: one row, named by the file's stem, with the reason.
void WriteUnreadable(const std::string& file, const std::string& reason, SetOutput* out) {
  const RunLabel label{fs::path(file).stem().string(), "", "", "", "", "set"};
  out->rows.Write(
      {label, file, nullptr, nullptr, std::nan(""), reason, out->a.time_limit, out->a.tolerance});
  out->table.push_back({fs::path(file).filename().string(), "-", "unreadable", {}, {}});
}

int RunSet(const RunArguments& a, const std::vector<std::string>& files,
           const std::vector<std::string>& unreadable,
           const std::vector<std::unique_ptr<Formulation>>& formulations,
           const RecordTarget& target, RunJson* record, std::string* reason) {
  SetOutput out{
      a, RecordFiles(target), RecordWriter<ProblemSetRow>(target, ProblemSetSchema()), {}, record};
  const Activity comparing("solving the problem set");
  for (std::size_t f = 0; f < files.size(); ++f) {
    const std::string& file = files[f];
    if (!unreadable[f].empty()) {
      WriteUnreadable(file, unreadable[f], &out);
      continue;
    }
    const Problem problem = LoadSetProblem(a, file);
    for (const SetStart& start : StartsOf(file, problem)) {
      for (const auto& formulation : formulations) {
        if (!SolveOne(file, problem, *formulation, start, &out)) {
          AcknowledgeInterrupt();
          *reason = "interrupted during " + problem.name + " " + formulation->name();
          return kExitInterrupted;
        }
      }
    }
  }
  const auto unread = std::count_if(unreadable.begin(), unreadable.end(),
                                    [](const std::string& r) { return !r.empty(); });
  *reason = "every formulation was run on every problem (problems.csv holds each outcome)";
  if (unread > 0) {
    *reason += "; " + std::to_string(unread) + " of " + std::to_string(files.size()) +
               " files could not be read (status unreadable)";
  }
  std::fprintf(stderr, "%scompare: records in %s\n", CompareTable(out.table).c_str(),
               target.memory != nullptr ? "memory" : target.directory.c_str());
  return kExitOk;
}

}  // namespace

std::vector<std::string> ProblemSetFiles(const std::string& items) {
  std::vector<std::string> files;
  for (const auto& item : SplitItems(items)) {
    std::error_code ec;
    if (fs::is_directory(item, ec)) {
      for (auto& file : ProblemFilesIn(item)) files.push_back(std::move(file));
    } else if (fs::is_regular_file(item, ec)) {
      files.push_back(item);
    } else {
      throw InputError("--problem-dir: '" + item + "' is neither a directory nor a file");
    }
  }
  if (files.empty()) throw InputError("--problem-dir: names no problem file");
  std::set<std::string> seen;
  for (const auto& file : files) {
    if (!seen.insert(fs::weakly_canonical(file).string()).second) {
      throw InputError("--problem-dir: '" + file + "' is named twice");
    }
  }
  return files;
}

int ProblemSetCommand(const RunArguments& a, RunJson* record, RecordTexts* memory) {
  const std::vector<std::string> files = ProblemSetFiles(a.problem_dir);
  if (Distributed()) throw UsageError("compare: runs in one process only (not mpirun)");
  const auto formulations = MakeFormulations(a);
  const std::vector<std::string> unreadable = CheckFiles(a, files, record);
  record->problem = fs::path(files.front()).parent_path().filename().string();
  record->problem_source = "--problem-dir " + a.problem_dir;
  record->settings = a.settings;
  record->tolerance = a.tolerance;
  record->time_limit_s = a.time_limit;
  for (const auto& f : formulations) record->formulations.push_back(f->name());
  record->starts = {"cold", "guess:K"};
  record->mode = "set";
  record->repeat = a.repeat;
  return WithRecords(a, record, memory, [&](const RecordTarget& target, std::string* reason) {
    return RunSet(a, files, unreadable, formulations, target, record, reason);
  });
}

std::optional<State> GuessStart(const RunArguments& a, const Problem& problem) {
  if (a.start_guess <= 0) return std::nullopt;
  if (a.problem_file.empty() || !io::IsFclibPath(a.problem_file)) {
    throw InputError("--start guess:" + std::to_string(a.start_guess) +
                     ": only for an FCLIB file (--problem-file F.hdf5) with /guesses");
  }
  const io::FclibAnswers answers = io::LoadFclibAnswers(a.problem_file);
  if (static_cast<std::size_t>(a.start_guess) > answers.guesses.size()) {
    throw InputError("--start guess:" + std::to_string(a.start_guess) + ": " + a.problem_file +
                     " has " + std::to_string(answers.guesses.size()) + " guesses (/guesses)");
  }
  State guess = ZeroState(*problem.model);
  guess.u = answers.guesses[static_cast<std::size_t>(a.start_guess) - 1].u;
  guess.r = answers.guesses[static_cast<std::size_t>(a.start_guess) - 1].r;
  return guess;
}

}  // namespace cb::harness
