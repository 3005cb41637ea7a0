// DIR/run.json: what a run or comparison was and how it ended, so that a directory of records
// says what made it and `contactbench rerun` can make it again: the suite's version, commit,
// binary, compiler and flags, the version of every linked library, the machine (CPU, cores,
// host) and its load at the start and the end, the process count, the command line, the
// problem and where it came from (a problem file's copy with its hash), the settings that
// decide a verdict, the exit status with its reason, counts and the total wall time. Written at the
// end of every run and comparison, including one that was interrupted or stopped on a failure
// (docs/records.md describes the fields).
#pragma once

#include <array>
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "harness/machine.h"
#include "harness/run_inputs.h"

namespace cb::harness {

struct RunJson {
  std::vector<std::string> command_line;   // argv, the program's name first
  std::string command;                     // "run" or "compare"
  std::string problem;                     // the problem's name ("" if not loaded)
  std::string problem_source;              // "--problem NAME" or "--problem-file F"
  std::vector<std::string> problem_notes;  // what reading the file changed (Problem::notes)
  std::string control;  // what control_disp is: Problem::control_label ("" if none)
  std::map<std::string, std::string> settings;  // --set
  std::vector<std::string> formulations;
  std::string reference;  // compare: the reference formulation ("" for free mode)
  std::string mode;       // compare: replay or free
  std::vector<std::string> starts;
  double tolerance = 0.0;
  double time_limit_s = 0.0;  // 0: none
  int repeat = 1;             // compare --repeat
  std::chrono::system_clock::time_point started = std::chrono::system_clock::now();
  std::chrono::steady_clock::time_point started_steady = std::chrono::steady_clock::now();
  std::array<double, 3> load_at_start = LoadAverage();
  std::vector<CopiedInput> inputs;  // --problem-file: the copies in --out (run_inputs.h)
  std::string rerun_of;             // `contactbench rerun DIR`: DIR
  // Counts over every run of the command (a comparison sums its runs).
  int runs = 0;
  int attempts = 0;
  int accepted_steps = 0;
  int kinks = 0;
  int repeat_disagreements = 0;  // solves whose repetitions disagreed with the first answer
};

// The executable of this process (/proc/self/exe), and the SHA-256 of a file's bytes ("" when
// it cannot be read): run.json's build.binary and build.binary_sha256.
std::string RunningBinary();
std::string BinarySha256(const std::string& binary);

// The JSON text of `run`, ended with `exit_status` for `reason`.
std::string RunJsonText(const RunJson& run, int exit_status, const std::string& reason);

// Writes DIR/run.json (through a temporary file renamed into place); false if it could not be
// written, so that a run on a full disk still exits with the status of what stopped it.
bool WriteRunJson(const std::string& directory, const RunJson& run, int exit_status,
                  const std::string& reason);

}  // namespace cb::harness
