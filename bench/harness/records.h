// The run records of COMPARISON.md: long-format CSV, one row per step attempt, per iteration,
// per kink, written and flushed as they are produced; the final state, the problem's
// parameters and a comparison's outcomes at the end. One RecordFiles holds the files of an
// output directory; each run writes into them through a RunRecorder that labels every row, so
// a comparison puts all its runs in one long table. The columns are those of
// record_schemas.h; docs/records.md describes them.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "harness/progress.h"
#include "harness/record_schemas.h"
#include "path/path.h"
#include "problems/problem.h"

namespace cb::harness {

class RecordFiles {
 public:
  // Opens DIR/steps.csv, DIR/iterations.csv, DIR/kinks.csv and DIR/critical.csv (limit and
  // bifurcation points; the directory must exist).
  explicit RecordFiles(const RecordTarget& target);
  RecordWriter<AttemptRow>& steps() { return steps_; }
  RecordWriter<IterationRow>& iterations() { return iterations_; }
  RecordWriter<KinkRow>& kinks() { return kinks_; }
  RecordWriter<CriticalRow>& critical() { return critical_; }

 private:
  RecordWriter<AttemptRow> steps_;
  RecordWriter<IterationRow> iterations_;
  RecordWriter<KinkRow> kinks_;
  RecordWriter<CriticalRow> critical_;
};

class RunRecorder final : public PathObserver {
 public:
  // `total_steps` is for the progress line (shown on a terminal only).
  RunRecorder(RecordFiles* files, const Problem& problem, RunLabel label, int total_steps);

  void OnAttempt(const StepAttempt& attempt) override;
  void OnKink(const KinkRecord& kink) override;
  void OnCriticalPoint(const CriticalPointRecord& c) override;

  bool all_verified() const { return all_verified_; }
  int attempts() const { return attempts_; }
  int accepted() const { return accepted_; }
  int total_steps() const { return total_steps_; }
  // Per attempt, in order: the solver's iterations and the solve's wall time.
  const std::vector<int>& iterations() const { return iterations_; }
  const std::vector<double>& solve_times_s() const { return solve_times_s_; }
  // The fastest and the slowest time taken by any solve, repetitions included (NaN before the
  // first attempt).
  double fastest_solve_s() const { return fastest_solve_s_; }
  double slowest_solve_s() const { return slowest_solve_s_; }
  // Solves whose repetitions (compare --repeat) did not all give the first answer, and the
  // first of them ("step 3, repetition 2: 7 iterations, not 6"; "" when none).
  int repeat_disagreements() const { return repeat_disagreements_; }
  const std::string& first_disagreement() const { return first_disagreement_; }
  // Ends the progress line, so that a message after the run starts a line of its own.
  void EndProgress() { progress_.End(); }

 private:
  void ShowProgress(const StepAttempt& attempt);
  // steps.csv's fclib_error of a state: for a problem read from an FCLIB file and an LCP,
  // NaN otherwise (Problem::from_fclib).
  double StepFclibError(const State& state) const;

  RecordFiles* files_;
  const Problem& problem_;
  RunLabel label_;
  bool all_verified_ = true;
  int attempts_ = 0;
  int accepted_ = 0;
  int total_steps_ = 0;
  std::vector<int> iterations_;
  std::vector<double> solve_times_s_;
  double fastest_solve_s_ = std::numeric_limits<double>::quiet_NaN();
  double slowest_solve_s_ = std::numeric_limits<double>::quiet_NaN();
  int repeat_disagreements_ = 0;
  std::string first_disagreement_;
  ProgressLine progress_;  // on a terminal only
};

// The id the records give node `node` and obstacle `obstacle` of a body problem: the problem
// file's (Problem::node_ids, obstacle_ids), else the 0-based index.
std::int64_t NodeId(const Problem& problem, int node);
std::string ObstacleId(const Problem& problem, int obstacle);

// The rows of a body problem's state (step `step`, saved as `label`): one per node, one per
// pair.
std::vector<NodeRow> NodeRows(const Problem& problem, const State& state, int step,
                              std::string_view label);
std::vector<PairRow> PairRows(const Problem& problem, const State& state, int step,
                              std::string_view label);

// The final state (the last accepted one, reached at step `step`): DIR/solution.csv and
// DIR/contacts.csv for a body, DIR/solution.csv (z and w = M z + q) for an LCP.
void WriteFinalState(const RecordTarget& target, const Problem& problem, const State& state,
                     int step);

// DIR/parameters.csv: the problem's parameters, reconstruction choices included, then the
// model's sizes.
void WriteParameters(const RecordTarget& target, const Problem& problem);

}  // namespace cb::harness
