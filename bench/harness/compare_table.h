// The table `contactbench compare` ends with: one line per formulation x start with its
// success (steps accepted of the steps asked for), the median iterations and the median wall
// time of its solves with the fastest and slowest solve (over the steps, and over the
// repetitions of compare --repeat), so that the outcome is seen without opening runs.csv.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace cb::harness {

struct CompareTableRow {
  std::string formulation;
  std::string start;
  std::string outcome;                                          // "accepted/asked", or "skipped"
  std::vector<int> iterations;                                  // per solve
  std::vector<double> solve_times;                              // per solve, seconds
  double fastest_s = std::numeric_limits<double>::quiet_NaN();  // any solve, repetitions too
  double slowest_s = std::numeric_limits<double>::quiet_NaN();
};

// The table as aligned plain text, a header line first.
std::string CompareTable(const std::vector<CompareTableRow>& rows);

}  // namespace cb::harness
