// The memory estimate of a distributed iterative solve (linear=amg; bench/harness/memory_budget.h)
// against the peaks the scale benchmark measured (scripts/scale_benchmark.sh, the committed
// results/scale/*.csv with a `problem` column): for every verified amg run, the estimate made
// for its problem, size and processes is an upper bound of the processes' summed peak resident
// memory, by at most 2 times (docs/hardening.md, "Memory").
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_contactbench.h"
#include "source_tree.h"

namespace cb {
namespace {
#ifdef CONTACTBENCH_HAVE_PETSC  // the runs are of a distributed formulation

using Row = std::map<std::string, std::string>;

std::vector<std::string> Cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

// The verified amg rows of the scale benchmark's records that name their problem.
std::vector<Row> MeasuredAmgRuns() {
  std::vector<Row> rows;
  const auto folder = testing_support::SourceRoot() / "results" / "scale";
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    std::ifstream in(entry.path());
    std::string line;
    if (entry.path().extension() != ".csv" || !std::getline(in, line)) continue;
    const std::vector<std::string> header = Cells(line);
    if (std::find(header.begin(), header.end(), "problem") == header.end() ||
        std::find(header.begin(), header.end(), "max_rss_mb_per_process") == header.end()) {
      continue;
    }
    while (std::getline(in, line)) {
      const std::vector<std::string> cells = Cells(line);
      Row row;
      for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
      if (row["linear_solve"] == "amg" && row["verified"] == "true") rows.push_back(row);
    }
  }
  return rows;
}

// The estimate in MiB for `row`'s run, refused under a 1-byte limit; -1 when not refused.
double EstimatedMib(const Row& row) {
  std::string settings = " --set n=" + row.at("n");
  if (row.at("problem") == "hertz-3d") settings += " --set nz=" + row.at("n") + " --set grading=1";
  // The estimate is made before MPI starts, from the launcher's process count.
  const auto out = testing_support::RunContactbench(
      "run --problem " + row.at("problem") + settings + " --formulation " + row.at("formulation") +
          " --option linear=amg --out " +
          (std::filesystem::temp_directory_path() / "contactbench_iterative_estimate_never")
              .string(),
      "2>&1", "env CONTACTBENCH_MEMORY_LIMIT=1 OMPI_COMM_WORLD_SIZE=" + row.at("processes"));
  const std::string key = "needs an estimated ";
  const auto at = out.output.find(key);
  if (out.status != 2 || at == std::string::npos) return -1.0;
  return std::stod(out.output.substr(at + key.size())) * 1024.0;
}

TEST(MemoryEstimateIterativeTest, BoundsEveryMeasuredAmgRunWithinTwice) {
  const std::vector<Row> runs = MeasuredAmgRuns();
  ASSERT_FALSE(runs.empty()) << "no scale-benchmark amg records under results/scale";
  bool three_d = false;
  for (const Row& run : runs) {
    const double measured =
        std::stod(run.at("max_rss_mb_per_process")) * std::stod(run.at("processes"));
    const double estimate = EstimatedMib(run);
    const std::string what =
        run.at("problem") + " n = " + run.at("n") + " on " + run.at("processes") + " processes";
    EXPECT_GE(estimate, measured) << what;
    EXPECT_LE(estimate, 2.0 * measured) << what;
    three_d = three_d || run.at("problem") == "hertz-3d";
  }
  EXPECT_TRUE(three_d) << "no 3-D run among the records";
}
#endif  // CONTACTBENCH_HAVE_PETSC

}  // namespace
}  // namespace cb
