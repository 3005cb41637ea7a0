// `contactbench rerun DIR --out NEW`: the command a run's run.json records, made again into
// NEW, with the problem file's copy kept in DIR/problem/ in place of the original. What would
// make it another run (another binary or library, another BLAS, another process count, a copy
// whose hash is not the recorded one) is listed, for the command to refuse unless forced.
#pragma once

#include <string>
#include <vector>

namespace cb::harness {

struct RerunPlan {
  std::string command;                   // "run" or "compare"
  std::vector<std::string> arguments;    // after the command's name: --out NEW, the copies
  std::vector<std::string> differences;  // why it would not be the same run ("" none)
};

// Reads DIR/run.json; throws InputError naming DIR and what is wrong with it (no such
// directory, no run.json, not JSON, a field missing, a command that cannot be rerun).
RerunPlan PlanRerun(const std::string& dir, const std::string& out, bool overwrite);

}  // namespace cb::harness
