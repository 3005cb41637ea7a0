// What the suite driver says to its user: the version, the suggestions for a mistyped name,
// the usage only after an argument error, the summary of a fixed-load run and the table that
// ends a comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/median.h"
#include "harness/compare_table.h"
#include "harness/suggest.h"
#include "refusal.h"
#include "run_contactbench.h"
#include "source_tree.h"

namespace {

using Outcome = ::cb::testing_support::CliOutcome;
using ::cb::testing_support::At;
using ::cb::testing_support::RefusedOption;

// `contactbench ARGS` with `streams` ("2>&1", "2>/dev/null", "2>&1 >/dev/null").
Outcome RunCli(const std::string& args, const std::string& streams = "2>&1") {
  return ::cb::testing_support::RunContactbench(args, streams);
}

const std::filesystem::path kExamples = ::cb::testing_support::SourceRoot() / "examples";

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_messages_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

TEST(SuggestTest, EditDistanceCountsInsertionsDeletionsAndSubstitutions) {
  using cb::harness::EditDistance;
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("abc", ""), 3u);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("newton", "newtn"), 1u);
  EXPECT_EQ(EditDistance("implicit_fb", "implicit-fb"), 1u);
  EXPECT_EQ(EditDistance("ab", "ba"), 2u);  // a transposition is two edits
}

TEST(SuggestTest, TheNearestCandidateIsSuggestedOnlyWhenNear) {
  using cb::harness::ClosestMatch;
  const std::vector<std::string> solvers = {"newton", "dogleg", "quasi-newton"};
  EXPECT_EQ(ClosestMatch("newtn", solvers), "newton");
  EXPECT_EQ(ClosestMatch("quasi", solvers), "quasi-newton");  // the only extension
  EXPECT_EQ(ClosestMatch("dolgeg", solvers), "dogleg");
  EXPECT_EQ(ClosestMatch("cholesky", solvers), std::nullopt);
  EXPECT_EQ(ClosestMatch("", solvers), std::nullopt);
}

TEST(CliMessagesTest, VersionPrintsTheVersionAndCommit) {
  const Outcome o = RunCli("--version", "2>/dev/null");
  EXPECT_EQ(o.status, 0);
  EXPECT_EQ(o.output.rfind("contactbench 0.", 0), 0u) << o.output;
  EXPECT_NE(o.output.find("commit"), std::string::npos) << o.output;
}

TEST(CliMessagesTest, AMistypedNameSuggestsTheClosestValidOne) {
  const auto dir = TempDir("suggest").string();
  struct Case {
    std::string args, suggestion;  // the closest valid name, which the refusal names
  };
  const Case cases[] = {
      {"rn", "run"},
      {"run --problme block --formulation implicit-fb --out " + dir, "--problem"},
      {"run --problem blok --formulation implicit-fb --out " + dir, "block"},
      {"run --problem block --formulation implicit_fb --out " + dir, "implicit-fb"},
      {"run --problem block --formulation implicit-fb --solver newtn --out " + dir, "newton"},
      {"compare --problem block --formulations implicit-fb,nonsmoth-fb --out " + dir,
       "nonsmooth-fb"},
      // A problem parameter (--set), of a named problem and of a problem file.
      {"run --problem block --set youngs_modulos=1 --formulation implicit-fb --out " + dir,
       "youngs_modulus"},
      {"run --problem-file " + (kExamples / "truss-2d-bar-wall.json").string() +
           " --set arc_lenght=0.1 --formulation implicit-fb --out " + dir,
       "arc_length"},
      // A formulation's own option (--option), in run and in compare.
      {"run --problem block --formulation implicit-fb --option gama_tol=1e-3 --out " + dir,
       "gamma_tol"},
      {"compare --problem block --formulations implicit-fb,nonsmooth-fb --option "
       "implicit-fb:rho_mn=1e-9 --out " +
           dir,
       "rho_min"},
  };
  for (const Case& c : cases) {
    const Outcome o = RunCli(c.args);
    EXPECT_EQ(o.status, 2) << c.args;
    EXPECT_TRUE(RefusedOption(o.output, At("", {"'" + c.suggestion + "'"}))) << c.args;
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
}

TEST(CliMessagesTest, TheUsageFollowsArgumentErrorsOnlyAndGoesToStandardError) {
  // An argument error: the message and the command's usage, on standard error only.
  const Outcome argument = RunCli("run --problem block --out x", "2>&1 >/dev/null");
  EXPECT_EQ(argument.status, 2);
  EXPECT_NE(argument.output.find("usage: contactbench run"), std::string::npos);
  EXPECT_EQ(RunCli("run --problem block --out x", "2>/dev/null").output, "");
  const Outcome nothing = RunCli("", "2>&1 >/dev/null");
  EXPECT_EQ(nothing.status, 2);
  EXPECT_NE(nothing.output.find("usage:"), std::string::npos);

  // A data error: a clockwise Gmsh element is reported by its message alone.
  const auto dir = TempDir("clockwise");
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kExamples / "q4-block-gmsh.json", dir / "q4-block-gmsh.json");
  std::ifstream mesh_in(kExamples / "q4-block-gmsh.msh");
  std::string mesh((std::istreambuf_iterator<char>(mesh_in)), std::istreambuf_iterator<char>());
  const std::string counter_clockwise = "\n6 1 5 6 4\n";
  ASSERT_NE(mesh.find(counter_clockwise), std::string::npos);
  mesh.replace(mesh.find(counter_clockwise), counter_clockwise.size(), "\n6 1 4 6 5\n");
  std::ofstream(dir / "q4-block-gmsh.msh") << mesh;
  const Outcome data = RunCli("run --problem-file " + (dir / "q4-block-gmsh.json").string() +
                              " --formulation implicit-fb --out " + (dir / "out").string());
  EXPECT_EQ(data.status, 2);
  EXPECT_TRUE(RefusedOption(data.output, At("", {"clockwise"}))) << data.output;
  EXPECT_EQ(data.output.find("usage"), std::string::npos) << data.output;
  EXPECT_EQ(std::count(data.output.begin(), data.output.end(), '\n'), 1) << data.output;
  std::filesystem::remove_all(dir);
}

TEST(CliMessagesTest, AFixedLoadRunSummarisesItsIterationsAndTime) {
  const auto dir = TempDir("fixed_load");
  const Outcome o = RunCli("run --problem-file " + (kExamples / "lcp-dense-2x2.json").string() +
                           " --formulation implicit-fb --out " + dir.string());
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find(" iterations, "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(" s) -> "), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("kinks"), std::string::npos) << o.output;
  std::filesystem::remove_all(dir);
}

TEST(CliMessagesTest, CompareEndsWithATableOfEachFormulationAndStart) {
  const auto dir = TempDir("compare_table");
  const Outcome o =
      RunCli("compare --problem-file " + (kExamples / "lcp-dense-2x2.json").string() +
             " --formulations implicit-fb,nonsmooth-fb --starts warm,cold --out " + dir.string());
  EXPECT_EQ(o.status, 0) << o.output;
  const std::size_t header = o.output.find("formulation   start  success  median iterations");
  ASSERT_NE(header, std::string::npos) << o.output;
  for (const char* row : {"implicit-fb   warm   1/1", "implicit-fb   cold   1/1",
                          "nonsmooth-fb  warm   1/1", "nonsmooth-fb  cold   1/1"}) {
    EXPECT_NE(o.output.find(row, header), std::string::npos) << row << "\n" << o.output;
  }
  std::filesystem::remove_all(dir);
}

TEST(CliMessagesTest, PlotRunsThePlotScriptOnARunsDirectory) {
  const auto dir = TempDir("plot");
  ASSERT_EQ(RunCli("run --problem-file " + (kExamples / "truss-2d-bar-wall.json").string() +
                   " --formulation implicit-fb --out " + dir.string())
                .status,
            0);
  const auto figures = dir / "figures-of-step-14";
  const Outcome o = RunCli("plot " + dir.string() + " --step 14 --figures " + figures.string());
  EXPECT_EQ(o.status, 0) << o.output;
  for (const char* figure : {"path.png", "deformed.png", "cost.png", "residual.png"}) {
    EXPECT_GT(std::filesystem::file_size(figures / figure), 10000u) << figure << "\n" << o.output;
  }
  // No directory: an argument error; a directory without records: the script's message.
  const Outcome missing = RunCli("plot");
  EXPECT_EQ(missing.status, 2);
  EXPECT_TRUE(RefusedOption(missing.output, At("", {"OUT_DIR"}))) << missing.output;
  EXPECT_NE(missing.output.find("usage: contactbench plot OUT_DIR"), std::string::npos);
  const Outcome empty = RunCli("plot " + (dir / "vtk").string());
  EXPECT_EQ(empty.status, 2);
  EXPECT_NE(empty.output.find("steps.csv"), std::string::npos) << empty.output;  // what is missing
  std::filesystem::remove_all(dir);
}

TEST(CompareTableTest, MediansOfOddAndEvenCounts) {
  using cb::Median;
  EXPECT_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_TRUE(std::isnan(Median({})));
}

TEST(CompareTableTest, ColumnsAreAlignedAndASkippedRunHasNoMedians) {
  const std::string table = cb::harness::CompareTable(
      {{"implicit-fb", "warm", "3/4", {2, 5, 3, 9}, {1e-3, 2e-3, 4e-3, 5e-3}, 0.5e-3, 6e-3},
       {"ipopt-energy", "cold", "skipped", {}, {}}});
  EXPECT_EQ(table,
            "formulation   start  success  median iterations  median time  range\n"
            "implicit-fb   warm   3/4      4                  3 ms         500 us - 6 ms\n"
            "ipopt-energy  cold   skipped  -                  -            -\n");
}

TEST(CliMessagesTest, TheSummaryLineCountsOnceAndNamesThePlotCommand) {
  const auto dir = TempDir("summary");
  const Outcome o = RunCli("run --problem two-bar --formulation implicit-fb --out " + dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  // "two-bar implicit-fb: path traced: N accepted steps, ... -> DIR", the count said once.
  EXPECT_NE(o.output.find("two-bar implicit-fb: path traced: "), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("steps accepted"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("\nplot: contactbench plot " + dir.string() + "\n"), std::string::npos)
      << o.output;
  std::filesystem::remove_all(dir);
}

TEST(CliMessagesTest, ListsTakeSpacesAfterTheirCommas) {
  const auto dir = TempDir("spaces");
  const Outcome o = RunCli(
      "compare --problem two-bar --formulations 'implicit-fb, nonsmooth-fb' "
      "--starts 'warm , cold' --out " +
      dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const std::string runs = [&] {
    std::ifstream in(dir / "runs.csv");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  for (const char* name : {"implicit-fb,", "nonsmooth-fb,", ",cold,", ",warm,"}) {
    EXPECT_NE(runs.find(name), std::string::npos) << name << "\n" << runs;
  }
  // A blank item is still an empty name.
  const Outcome blank = RunCli(
      "compare --problem two-bar --formulations 'implicit-fb, ,nonsmooth-fb' "
      "--out " +
      dir.string());
  EXPECT_EQ(blank.status, 2) << blank.output;
  EXPECT_TRUE(RefusedOption(blank.output, At("--formulations", {"'implicit-fb, ,nonsmooth-fb'"})));
  std::filesystem::remove_all(dir);
}

}  // namespace
