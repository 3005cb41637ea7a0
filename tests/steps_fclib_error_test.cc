// steps.csv's fclib_error (bench/harness/record_schemas.cc): the FCLIB literature's error of
// every attempt's state, the same figure as problems.csv's for a problem set's solve, defined
// for an FCLIB file and nan where it is not (src/verdict/natural_map_error.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "io/fclib_file.h"
#include "record_table.h"
#include "run_contactbench.h"
#include "source_tree.h"

namespace cb {
namespace {

using ::cb::testing_support::RunContactbench;
using ::cb::testing_support::Table;

const std::filesystem::path kRoot = ::cb::testing_support::SourceRoot();
const std::string kBoxStacks = (kRoot / "tests/data/fclib/Box_Stacks-i0122-82-5.hdf5").string();

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_steps_fclib_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A verified answer of the active-set method is exact up to rounding: its FCLIB error is far
// below the 1e-6 the problem-set test allows every verified answer (problem_set_test.cc).
constexpr double kVerifiedBound = 1e-6;

// A run on an FCLIB file: one row per attempt with a finite error; a problem set's solve of the
// same file: steps.csv's error is problems.csv's, row for row.
TEST(StepsFclibError, AnFclibFileHasItPerStepAsProblemsCsvHasIt) {
  if (!io::FclibAvailable()) GTEST_SKIP() << "built without HDF5";
  const auto dir = TempDir("fclib");
  const auto run =
      RunContactbench("run --problem-file " + kBoxStacks +
                      " --set friction=ignore --formulation active-set --start cold --out " +
                      (dir / "run").string());
  ASSERT_EQ(run.status, 0) << run.output;
  const auto steps = Table(dir / "run" / "steps.csv");
  ASSERT_FALSE(steps.empty());
  for (const auto& row : steps) {
    ASSERT_TRUE(row.count("fclib_error")) << "no fclib_error column";
    const double error = std::stod(row.at("fclib_error"));
    EXPECT_TRUE(std::isfinite(error)) << row.at("fclib_error");
    if (row.at("verified") == "true") {
      EXPECT_LT(error, kVerifiedBound);
    }
  }

  // A local (LCP) and a global (a finite-element body) FCLIB problem.
  const std::string cube = (kRoot / "tests/data/fclib/CubeH8.hdf5").string();
  const auto set = RunContactbench("compare --problem-dir " + kBoxStacks + "," + cube +
                                   " --set friction=ignore --formulations active-set --out " +
                                   (dir / "set").string());
  ASSERT_EQ(set.status, 0) << set.output;
  const auto set_steps = Table(dir / "set" / "steps.csv");
  const auto problems = Table(dir / "set" / "problems.csv");
  ASSERT_EQ(set_steps.size(), problems.size());  // one attempt per fixed-load solve
  for (std::size_t k = 0; k < problems.size(); ++k) {
    EXPECT_EQ(set_steps[k].at("start"), problems[k].at("start"));
    EXPECT_EQ(set_steps[k].at("fclib_error"), problems[k].at("fclib_error"));
    const double error = std::stod(problems[k].at("fclib_error"));
    EXPECT_TRUE(std::isfinite(error)) << problems[k].at("problem");
    if (problems[k].at("status") == "verified") {
      EXPECT_LT(error, kVerifiedBound);
    }
  }
  // The run's cold solve is the set's cold solve: the same figure.
  EXPECT_EQ(problems.at(0).at("start"), "cold");
  EXPECT_EQ(steps.back().at("fclib_error"), problems.at(0).at("fclib_error"));
}

// Where it is not defined, every step says nan, as problems.csv would: P1 `block` (linear, but
// held by its contacts alone: K is singular) and a truss traced by arc length (nonlinear).
TEST(StepsFclibError, NanWhereItIsNotDefined) {
  const auto dir = TempDir("suite");
  const auto block = RunContactbench(
      "run --problem block --set n=8 --formulation active-set --out " + (dir / "block").string());
  ASSERT_EQ(block.status, 0) << block.output;
  const auto block_steps = Table(dir / "block" / "steps.csv");
  ASSERT_EQ(block_steps.size(), 1u);
  EXPECT_EQ(block_steps[0].at("verified"), "true");
  EXPECT_EQ(block_steps[0].at("fclib_error"), "nan");

  const auto truss =
      RunContactbench("run --problem-file " + (kRoot / "examples/truss-2d-bar-wall.json").string() +
                      " --steps 3 --formulation implicit-fb --out " + (dir / "truss").string());
  ASSERT_EQ(truss.status, 0) << truss.output;
  const auto truss_steps = Table(dir / "truss" / "steps.csv");
  ASSERT_GE(truss_steps.size(), 3u);
  for (const auto& row : truss_steps) EXPECT_EQ(row.at("fclib_error"), "nan");
}

}  // namespace
}  // namespace cb
