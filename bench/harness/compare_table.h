// The table `contactbench compare` ends with: one line per formulation x start with its
// success (steps accepted of the steps asked for), the median iterations and the median wall
// time of its solves, so that the outcome is seen without opening runs.csv.
#pragma once

#include <string>
#include <vector>

namespace cb::harness {

struct CompareTableRow {
  std::string formulation;
  std::string start;
  std::string outcome;              // "accepted/asked", or "skipped"
  std::vector<int> iterations;      // per solve
  std::vector<double> solve_times;  // per solve, seconds
};

// The table as aligned plain text, a header line first.
std::string CompareTable(const std::vector<CompareTableRow>& rows);

}  // namespace cb::harness
