// The run records of COMPARISON.md: long-format CSV, one row per step attempt, per iteration,
// per kink, written and flushed as they are produced; solution and contact snapshots at the end.
// One RecordFiles holds the files of an output directory; each run writes into them through a
// RunRecorder that labels every row, so a comparison puts all its runs in one long table.
#pragma once

#include <memory>
#include <string>

#include "core/csv.h"
#include "path/path.h"
#include "problems/problem.h"

namespace cb::harness {

// Identifies a run in every row.
struct RunLabel {
  std::string problem;
  std::string formulation;
  std::string solver;
  std::string settings;
  std::string start;
  std::string mode;  // "run" (contactbench run), "replay" or "free" (contactbench compare)
};

class RecordFiles {
 public:
  // Opens DIR/steps.csv, DIR/iterations.csv, DIR/kinks.csv and DIR/critical.csv (limit and
  // bifurcation points; the directory must exist).
  explicit RecordFiles(const std::string& directory);
  const std::string& directory() const { return directory_; }
  CsvWriter& steps() { return *steps_; }
  CsvWriter& iterations() { return *iterations_; }
  CsvWriter& kinks() { return *kinks_; }
  CsvWriter& critical() { return *critical_; }

 private:
  std::string directory_;
  std::unique_ptr<CsvWriter> steps_, iterations_, kinks_, critical_;
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

 private:
  double ControlDisplacement(const State& state) const;

  RecordFiles* files_;
  const Problem& problem_;
  RunLabel label_;
  bool all_verified_ = true;
  int attempts_ = 0;
  int accepted_ = 0;
  int total_steps_ = 0;
  bool progress_ = false;  // on a terminal only
};

// DIR/solution.csv and DIR/contacts.csv for a state (the last accepted one).
void WriteSnapshot(const std::string& directory, const Problem& problem, const State& state,
                   int step);

}  // namespace cb::harness
