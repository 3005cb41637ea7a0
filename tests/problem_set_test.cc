// compare --problem-dir (bench/harness/problem_set.h) and run --start guess:K through the CLI:
// every problem x formulation x start gets a row whose status is the verdict's, bad sets are
// refused before any work, and a guess is the start of the solve.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "formulations/registry.h"
#include "io/fclib_file.h"
#include "path/path.h"
#include "problems/problem.h"
#include "refusal.h"
#include "run_contactbench.h"
#include "source_tree.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

using ::cb::testing_support::RunContactbench;

const std::filesystem::path kData = ::cb::testing_support::SourceRoot() / "tests/data/fclib";

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_problem_set_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A CSV file as rows of column -> value (the records have no quoted commas in these columns).
std::vector<std::map<std::string, std::string>> ReadCsv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream names(line);
  for (std::string name; std::getline(names, name, ',');) header.push_back(name);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream cells(line);
    std::map<std::string, std::string> row;
    std::string cell;
    for (std::size_t k = 0; k < header.size() && std::getline(cells, cell, ','); ++k) {
      row[header[k]] = cell;
    }
    rows.push_back(row);
  }
  return rows;
}

// A second method beside the active set: Siconos' Lemke where this build has Siconos (the
// sanitizer build has not), else the semismooth Fischer-Burmeister method.
std::string SecondMethod() {
  for (const auto& info : FormulationRegistry()) {
    if (info.name == "siconos-lemke" && info.available) return info.name;
  }
  return "nonsmooth-fb";
}

class ProblemSet : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!io::FclibAvailable()) GTEST_SKIP() << "built without HDF5";
  }
};

// Five files, two of which have one guess: 7 starts x 2 formulations; each row's status is the
// verdict of its attempt in steps.csv, and a verified answer has a small FCLIB error.
TEST_F(ProblemSet, EveryProblemFormulationAndStartIsJudged) {
  const auto dir = TempDir("all");
  const auto out =
      RunContactbench("compare --problem-dir " + kData.string() +
                      " --set friction=ignore --formulations active-set," + SecondMethod() +
                      " --time-limit 5 --out " + (dir / "out").string());
  ASSERT_EQ(out.status, 0) << out.output;
  const auto rows = ReadCsv(dir / "out" / "problems.csv");
  const auto steps = ReadCsv(dir / "out" / "steps.csv");
  ASSERT_EQ(rows.size(), 14u);
  ASSERT_EQ(steps.size(), 14u);  // one attempt per solve: nobody refuses an LCP or a body
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "runs.csv"));
  int guesses = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& row = rows[k];
    EXPECT_EQ(steps[k].at("problem"), row.at("problem"));
    EXPECT_EQ(steps[k].at("start"), row.at("start"));
    EXPECT_EQ(steps[k].at("mode"), "set");
    EXPECT_EQ(row.at("status"), steps[k].at("verified") == "true" ? "verified" : "failed")
        << row.at("problem") << " " << row.at("formulation");
    if (row.at("status") == "verified") {
      EXPECT_LT(std::stod(row.at("fclib_error")), 1e-6);
    }
    guesses += row.at("start").rfind("guess:", 0) == 0;
  }
  EXPECT_EQ(guesses, 4);
}

TEST_F(ProblemSet, ASkippedFormulationIsARowWithTheReason) {
  const auto dir = TempDir("skipped");
  const auto out = RunContactbench(
      "compare --problem-dir " + (kData / "Capsules-i125-1213.hdf5").string() +
      " --set friction=ignore --formulations ipopt-energy --out " + (dir / "out").string());
  ASSERT_EQ(out.status, 0) << out.output;
  const auto rows = ReadCsv(dir / "out" / "problems.csv");
  ASSERT_EQ(rows.size(), 2u);  // cold and the file's guess
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "skipped");
    EXPECT_EQ(row.at("fclib_error"), "nan");
    // What the model lacks for the energy formulation.
    EXPECT_TRUE(testing_support::Names(row.at("message"), {"has_energy()"}));
  }
}

// A directory of the suite's own JSON problem files beside an FCLIB file: each read and solved
// (a Gmsh mesh is read through the JSON file that names it, not as a problem of its own); a
// file that cannot be read (no JSON, a problem traced by arc length) is a row with the reason,
// and the set goes on. A list of files (comma-separated) is a set too.
TEST_F(ProblemSet, JsonFilesJoinTheSetAndUnreadableOnesAreRows) {
  const auto dir = TempDir("mixed");
  const auto set = dir / "set";
  std::filesystem::create_directories(set);
  const auto examples = ::cb::testing_support::SourceRoot() / "examples";
  for (const char* name : {"q4-block-gmsh.json", "q4-block-gmsh.msh", "lcp-dense-2x2.json",
                           "truss-2d-bar-wall.json"}) {
    std::filesystem::copy_file(examples / name, set / name);
  }
  std::filesystem::copy_file(kData / "CubeH8.hdf5", set / "CubeH8.hdf5");
  std::ofstream(set / "broken.json") << "{ not json";
  const auto out = RunContactbench("compare --problem-dir " + set.string() +
                                   " --set friction=ignore --formulations active-set --out " +
                                   (dir / "out").string());
  ASSERT_EQ(out.status, 0) << out.output;
  std::map<std::string, std::map<std::string, std::string>> by_file;
  for (const auto& row : ReadCsv(dir / "out" / "problems.csv")) {
    by_file[std::filesystem::path(row.at("source")).filename().string()] = row;
  }
  ASSERT_EQ(by_file.size(), 5u);  // the mesh is no problem of its own
  for (const char* solved : {"CubeH8.hdf5", "q4-block-gmsh.json", "lcp-dense-2x2.json"}) {
    EXPECT_EQ(by_file.at(solved).at("status"), "verified") << solved;
    EXPECT_EQ(by_file.at(solved).at("formulation"), "active-set") << solved;
  }
  const auto& broken = by_file.at("broken.json");
  EXPECT_EQ(broken.at("status"), "unreadable");
  EXPECT_EQ(broken.at("formulation"), "");
  EXPECT_EQ(broken.at("fclib_error"), "nan");
  EXPECT_TRUE(testing_support::Names(broken.at("message"), {"broken.json"}));
  const auto& traced = by_file.at("truss-2d-bar-wall.json");
  EXPECT_EQ(traced.at("status"), "unreadable");
  // The file and why it is no member: it is traced by arc length.
  EXPECT_TRUE(
      testing_support::Names(traced.at("message"), {"truss-2d-bar-wall.json", "arc length"}));

  // The same files as a list: the unreadable one is a row there too.
  const auto listed =
      RunContactbench("compare --problem-dir " + (set / "lcp-dense-2x2.json").string() + "," +
                      (set / "broken.json").string() + " --formulations active-set --out " +
                      (dir / "list").string());
  ASSERT_EQ(listed.status, 0) << listed.output;
  const auto rows = ReadCsv(dir / "list" / "problems.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("status"), "verified");
  EXPECT_EQ(rows[1].at("status"), "unreadable");
}

TEST_F(ProblemSet, BadSetsAreRefusedBeforeAnyWork) {
  const auto dir = TempDir("refused");
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::string set = " --problem-dir " + kData.string();
  const Case cases[] = {
      {set, "friction=ignore"},  // the files have friction: refused as for --problem-file
      {set + " --set friction=ignore --starts cold", "--starts: not with --problem-dir"},
      {set + " --set friction=ignore --steps 3", "--steps: not with --problem-dir"},
      {" --problem-dir " + (dir / "missing").string(), "neither a directory nor a file"},
      {" --problem-dir " + dir.string(), "holds no problem file"},
      {set + "," + (kData / "CubeH8.hdf5").string() + " --set friction=ignore", "named twice"},
      {" --problem-dir " +
           (::cb::testing_support::SourceRoot() / "examples/truss-2d-bar-wall.json").string(),
       "traced by arc length"},
  };
  for (const Case& c : cases) {
    const auto out = RunContactbench("compare" + c.arguments + " --out " + (dir / "out").string());
    EXPECT_EQ(out.status, 2) << c.arguments << "\n" << out.output;
    EXPECT_NE(out.output.find(c.message), std::string::npos) << c.arguments << "\n" << out.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "problems.csv")) << c.arguments;
  }
}

int IterationsOf(const std::filesystem::path& out) {
  const auto steps = ReadCsv(out / "steps.csv");
  EXPECT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps.at(0).at("verified"), "true");
  return std::stoi(steps.at(0).at("iterations"));
}

// A guess is the start of the solve: P1 written with its own verified answer as /guesses/1
// takes no iteration from it, and more than that cold.
TEST_F(ProblemSet, RunStartsFromTheFilesGuess) {
  const auto dir = TempDir("guess");
  const Problem block = MakeProblem("block", {{"n", "4"}});
  const StepProblem step{block.model.get(), ZeroState(*block.model),
                         StepConstraint::FixedLoad(block.load), block.scales};
  StartPoint start;
  start.du = Vec::Zero(block.model->num_dofs());
  start.r = Vec::Zero(block.model->num_pairs());
  const StepResult solved =
      MakeFormulation("active-set", FormulationConfig())->Solve(step, start, SolveControls());
  ASSERT_TRUE(Judge(step, solved.point, 1e-8).verified) << solved.message;
  const io::FclibState answer{solved.point.du, solved.point.r};
  const std::string file = (dir / "block.hdf5").string();
  io::WriteFclibFile(block, file, nullptr, &answer);

  const std::string run = "run --problem-file " + file + " --formulation active-set --out ";
  const auto from_guess = RunContactbench(run + (dir / "guess").string() + " --start guess:1");
  ASSERT_EQ(from_guess.status, 0) << from_guess.output;
  const auto cold = RunContactbench(run + (dir / "cold").string() + " --start cold");
  ASSERT_EQ(cold.status, 0) << cold.output;
  EXPECT_EQ(IterationsOf(dir / "guess"), 0);
  EXPECT_GT(IterationsOf(dir / "cold"), 0);
  EXPECT_EQ(ReadCsv(dir / "guess" / "steps.csv").at(0).at("start"), "guess:1");

  const auto beyond = RunContactbench(run + (dir / "beyond").string() + " --start guess:2");
  EXPECT_EQ(beyond.status, 2) << beyond.output;
  // The option as given, the file and the number of guesses it has.
  EXPECT_TRUE(testing_support::RefusedOption(beyond.output,
                                             testing_support::At("--start guess:2", {file})));
  EXPECT_TRUE(testing_support::NamesNumber(testing_support::RefusalLine(beyond.output), 1));
  const auto named = RunContactbench("run --problem block --formulation active-set --out " +
                                     (dir / "named").string() + " --start guess:1");
  EXPECT_EQ(named.status, 2) << named.output;
  // The option as given, and the option it needs.
  EXPECT_TRUE(testing_support::RefusedOption(
      named.output, testing_support::At("--start guess:1", {"--problem-file"})));
}

}  // namespace
}  // namespace cb
