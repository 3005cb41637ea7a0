// The memory estimate made before a problem is built (bench/harness/memory_budget.h,
// docs/hardening.md "Memory") for the 3-D problems: their size known from the settings, the
// direct factor's fill in 3-D, the linear solver chosen; refused at once with the estimate, the
// machine's memory and the option that lifts the bound (issue 30).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "harness/memory_budget.h"
#include "run_contactbench.h"
#include "source_tree.h"

namespace {

using Outcome = cb::testing_support::CliOutcome;

// `contactbench run ARGUMENTS --out DIR` with CONTACTBENCH_MEMORY_LIMIT=`limit` ("" for the
// machine's own), ended after 60 s: a run that starts building instead of refusing fails.
Outcome RunWithLimit(const std::string& limit, const std::string& arguments) {
  // Each test (ctest runs them in parallel) and each process its own --out.
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("contactbench_memory_estimate_" + test + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  Outcome out = cb::testing_support::RunContactbench(
      "run " + arguments + " --out " + dir.string(), "2>&1",
      "timeout -s KILL 60 env" + (limit.empty() ? "" : " CONTACTBENCH_MEMORY_LIMIT=" + limit));
  EXPECT_FALSE(std::filesystem::exists(dir / "steps.csv")) << "work started: " << arguments;
  std::filesystem::remove_all(dir);
  return out;
}

// The estimate in GiB of a refusal ("... needs an estimated 4.52 GiB (..."), or -1.
double EstimatedGib(const std::string& output) {
  const std::string key = "needs an estimated ";
  const auto at = output.find(key);
  return at == std::string::npos ? -1.0 : std::stod(output.substr(at + key.size()));
}

// Refused in seconds, naming the estimate, the machine's memory and --allow-memory: before,
// both were built first (72 s and 7.2 GB, 75 s and 8 GB) and died out of memory.
TEST(MemoryEstimateTest, HugeThreeDimensionalProblemsAreRefusedAtOnce) {
  for (const char* args : {"--problem hertz-3d --set n=1000",
                           "--problem plate-3d --set nx=1000 --set ny=1000 --set nz=10"}) {
    const Outcome o = RunWithLimit("", std::string(args) + " --formulation implicit-fb");
    EXPECT_EQ(o.status, 2) << args << "\n" << o.output;
    EXPECT_LT(o.seconds, 20.0) << args;
    EXPECT_NE(o.output.find("needs an estimated"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("a 3-D direct factor's fill"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find(" available ("), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("--allow-memory runs it anyway"), std::string::npos) << o.output;
  }
}

// Within the stated factor of the peak resident memory measured for a direct solve of
// hertz-3d (docs/hardening.md, "Memory"; docs/scale-out.md): 1 to 2 times the peak.
TEST(MemoryEstimateTest, TheThreeDimensionalEstimateIsWithinItsFactorOfTheMeasuredPeak) {
  constexpr double kGib = 1024.0 * 1024.0 * 1024.0;
  const struct {
    int n;
    double peak_bytes;
  } measured[] = {{40, 4.3e9}, {54, 13.6e9}};
  for (const auto& m : measured) {
    const Outcome o =
        RunWithLimit("1", "--problem hertz-3d --set n=" + std::to_string(m.n) +
                              " --set nz=" + std::to_string(m.n) + " --formulation implicit-fb");
    ASSERT_EQ(o.status, 2) << o.output;
    const double ratio = EstimatedGib(o.output) * kGib / m.peak_bytes;
    EXPECT_GE(ratio, 1.0) << "n = " << m.n << ": " << o.output;
    EXPECT_LE(ratio, 2.0) << "n = " << m.n << ": " << o.output;
  }
}

// A problem file of Gmsh hexahedra is checked once built, with the fill of a 3-D mesh (its
// separator taken as a cube's); before, it was estimated as a 2-D mesh.
TEST(MemoryEstimateTest, AHexahedralProblemFileCountsTheThreeDimensionalFill) {
  const auto file = cb::testing_support::SourceRoot() / "tests/data/hex-block.json";
  const Outcome o =
      RunWithLimit("1", "--problem-file " + file.string() + " --formulation implicit-fb");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--problem-file " + file.string() + " needs an estimated"),
            std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("a 3-D direct factor's fill"), std::string::npos) << o.output;
}

// "1e3" is no integer (integers as digits): refused as such, not read as 1000.
TEST(MemoryEstimateTest, AnIntegerSizeIsDigits) {
  const Outcome o = RunWithLimit("", "--problem hertz-3d --set n=1e3 --formulation implicit-fb");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("'1e3' is not an integer"), std::string::npos) << o.output;
}

#ifdef CONTACTBENCH_HAVE_PETSC
// An iterative solve (dist-*'s linear=amg) has no factor: its estimate has no fill, but its
// own, larger, term per unknown (checked against measured peaks by
// memory_estimate_iterative_test.cc): in 3-D at n = 40 it is no smaller than the direct one's.
TEST(MemoryEstimateTest, TheLinearSolverChosenCountsItsFill) {
  const std::string problem = "--problem hertz-3d --set n=40 --set nz=40 ";
  const Outcome direct = RunWithLimit("1", problem + "--formulation dist-implicit-fb");
  const Outcome amg =
      RunWithLimit("1", problem + "--formulation dist-implicit-fb --option linear=amg");
  ASSERT_EQ(direct.status, 2) << direct.output;
  ASSERT_EQ(amg.status, 2) << amg.output;
  EXPECT_NE(direct.output.find("fill"), std::string::npos) << direct.output;
  EXPECT_EQ(amg.output.find("fill"), std::string::npos) << amg.output;
  const double dofs = 3.0 * 41.0 * 41.0 * 41.0;
  EXPECT_GE(EstimatedGib(amg.output) * 1024.0 * 1024.0 * 1024.0,
            dofs * cb::harness::kBytesPerUnknownIterative3d)
      << amg.output;
}
#endif

}  // namespace
