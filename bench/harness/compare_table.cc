#include "harness/compare_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/median.h"

namespace cb::harness {

namespace {

std::string Cell(const char* format, double value) {
  if (std::isnan(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// A time in the unit that keeps three significant digits readable: "3.55 us", "12.1 ms", "2.5 s".
std::string TimeCell(double seconds) {
  if (std::isnan(seconds)) return "-";
  if (seconds < 1e-3) return Cell("%.3g us", seconds * 1e6);
  if (seconds < 1.0) return Cell("%.3g ms", seconds * 1e3);
  return Cell("%.3g s", seconds);
}

// The fastest and slowest solve, "-" when there was none.
std::string RangeCell(double fastest, double slowest) {
  if (std::isnan(fastest) || std::isnan(slowest)) return "-";
  return TimeCell(fastest) + " - " + TimeCell(slowest);
}

}  // namespace

std::string CompareTable(const std::vector<CompareTableRow>& rows) {
  std::vector<std::vector<std::string>> cells = {
      {"formulation", "start", "success", "median iterations", "median time", "range"}};
  for (const CompareTableRow& row : rows) {
    const double iterations =
        Median(std::vector<double>(row.iterations.begin(), row.iterations.end()));
    cells.push_back({row.formulation, row.start, row.outcome, Cell("%g", iterations),
                     TimeCell(Median(row.solve_times)), RangeCell(row.fastest_s, row.slowest_s)});
  }
  std::vector<std::size_t> width(cells.front().size(), 0);
  for (const auto& line : cells) {
    for (std::size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
  }
  std::string text;
  for (const auto& line : cells) {
    std::string out;
    for (std::size_t c = 0; c < line.size(); ++c) {
      out += line[c];
      if (c + 1 < line.size()) out += std::string(width[c] - line[c].size() + 2, ' ');
    }
    text += out + "\n";
  }
  return text;
}

}  // namespace cb::harness
