// `contactbench compare --repeat N`: the option's checks, and the records of repeated solves
// (the median time with its range and the count of samples).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "record_table.h"
#include "run_contactbench.h"

namespace {

using cb::testing_support::RunContactbench;
using cb::testing_support::Table;

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_repeat_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

TEST(RepeatTest, ABadRepeatCountIsRefusedNamingTheOption) {
  const auto dir = TempDir("bad");
  for (const char* value : {"0", "-3", "2.5", "two", "1e2", ""}) {
    const auto o = RunContactbench("compare --problem two-bar-obstacle --repeat '" +
                                   std::string(value) + "' --out " + dir.string());
    EXPECT_EQ(o.status, 2) << value << ": " << o.output;
    EXPECT_NE(o.output.find("--repeat: "), std::string::npos) << value << ": " << o.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "steps.csv")) << value;
  }
  const auto missing =
      RunContactbench("compare --problem two-bar-obstacle --out " + dir.string() + " --repeat");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("--repeat needs a value"), std::string::npos) << missing.output;
  // Only compare times solves for a comparison.
  const auto run = RunContactbench(
      "run --problem two-bar-obstacle --formulation implicit-fb "
      "--repeat 3 --out " +
      dir.string());
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("unknown option '--repeat'"), std::string::npos) << run.output;
}

TEST(RepeatTest, EveryStepRecordsTheMedianTimeOfItsRepetitionsWithTheirRange) {
  const auto dir = TempDir("records");
  constexpr int kRepeat = 3;
  const auto o = RunContactbench(
      "compare --problem two-bar-obstacle --steps 12 --formulations implicit-fb,active-set "
      "--starts warm,cold --repeat " +
      std::to_string(kRepeat) + " --out " + dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto rows = Table(dir / "steps.csv");
  ASSERT_EQ(rows.size(), 2u * 2u * 12u);
  for (const auto& row : rows) {
    const double median = std::stod(row.at("time_s"));
    const double low = std::stod(row.at("time_min_s"));
    const double high = std::stod(row.at("time_max_s"));
    EXPECT_GT(low, 0.0);
    EXPECT_LE(low, median);
    EXPECT_LE(median, high);
    EXPECT_EQ(row.at("time_samples"), std::to_string(kRepeat));
    // The solvers are deterministic: their repetitions agree.
    EXPECT_EQ(row.at("repeats_agree"), "true") << row.at("formulation") << " " << row.at("step");
  }
  const auto run = nlohmann::json::parse(std::ifstream(dir / "run.json"));
  EXPECT_EQ(run.at("repeat").get<int>(), kRepeat);
  EXPECT_EQ(run.at("counts").at("repeat_disagreements").get<int>(), 0);
}

TEST(RepeatTest, WithoutRepeatEachTimeIsOneSample) {
  const auto dir = TempDir("once");
  const auto o = RunContactbench(
      "compare --problem two-bar-obstacle --steps 5 "
      "--formulations implicit-fb --out " +
      dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  for (const auto& row : Table(dir / "steps.csv")) {
    EXPECT_EQ(row.at("time_samples"), "1");
    EXPECT_EQ(row.at("time_min_s"), row.at("time_s"));
    EXPECT_EQ(row.at("time_max_s"), row.at("time_s"));
  }
}

}  // namespace
