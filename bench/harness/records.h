// The run records of COMPARISON.md: long-format CSV, one row per step attempt, per iteration,
// per kink, written and flushed as they are produced; solution and contact snapshots at the end.
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
};

class RunRecorder final : public PathObserver {
 public:
  // Opens DIR/steps.csv, DIR/iterations.csv and DIR/kinks.csv (the directory must exist).
  RunRecorder(const std::string& directory, const Problem& problem, RunLabel label);

  void OnAttempt(const StepAttempt& attempt) override;
  void OnKink(const KinkRecord& kink) override;

  // DIR/solution.csv and DIR/contacts.csv for a state (the last accepted one).
  void WriteSnapshot(const State& state, int step) const;

  bool all_verified() const { return all_verified_; }
  int attempts() const { return attempts_; }

 private:
  double ControlDisplacement(const State& state) const;

  std::string directory_;
  const Problem& problem_;
  RunLabel label_;
  std::unique_ptr<CsvWriter> steps_, iterations_, kinks_;
  bool all_verified_ = true;
  int attempts_ = 0;
  int total_steps_ = 0;
  bool progress_ = false;  // on a terminal only
};

}  // namespace cb::harness
