// DIR/run.json: what a run or comparison was and how it ended, so that a directory of records
// says what made it: the suite's version and commit, the command line, the problem and where
// it came from, the settings that decide a verdict, the exit status with its reason, counts and
// the total wall time. Written at the end of every run and comparison, including one that was
// interrupted or stopped on a failure (docs/records.md describes the fields).
#pragma once

#include <chrono>
#include <map>
#include <string>
#include <vector>

namespace cb::harness {

struct RunJson {
  std::vector<std::string> command_line;        // argv, the program's name first
  std::string command;                          // "run" or "compare"
  std::string problem;                          // the problem's name ("" if not loaded)
  std::string problem_source;                   // "--problem NAME" or "--problem-file F"
  std::vector<std::string> problem_notes;       // what reading the file changed (Problem::notes)
  std::map<std::string, std::string> settings;  // --set
  std::vector<std::string> formulations;
  std::string reference;  // compare: the reference formulation ("" for free mode)
  std::string mode;       // compare: replay or free
  std::vector<std::string> starts;
  double tolerance = 0.0;
  double time_limit_s = 0.0;  // 0: none
  std::chrono::system_clock::time_point started = std::chrono::system_clock::now();
  std::chrono::steady_clock::time_point started_steady = std::chrono::steady_clock::now();
  // Counts over every run of the command (a comparison sums its runs).
  int runs = 0;
  int attempts = 0;
  int accepted_steps = 0;
  int kinks = 0;
};

// The JSON text of `run`, ended with `exit_status` for `reason`.
std::string RunJsonText(const RunJson& run, int exit_status, const std::string& reason);

// Writes DIR/run.json (through a temporary file renamed into place); false if it could not be
// written, so that a run on a full disk still exits with the status of what stopped it.
bool WriteRunJson(const std::string& directory, const RunJson& run, int exit_status,
                  const std::string& reason);

}  // namespace cb::harness
