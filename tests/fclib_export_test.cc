// export --format fclib with the suite's answer (bench/harness/fclib_export.h): a fixed-load
// problem with its verified answer as /solution, and a path's step N at its load with step
// N - 1's state as /guesses/1; both answers verified on the problem read back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "formulations/registry.h"
#include "io/fclib_file.h"
#include "io/problem_file.h"
#include "path/path.h"
#include "problems/problem_path.h"
#include "run_contactbench.h"
#include "source_tree.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

using ::cb::testing_support::RunContactbench;

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_fclib_export_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// `state` as the answer of the fixed-load problem read from `file`, under the verdict.
bool VerifiedOnTheFile(const std::string& file, const io::FclibState& state) {
  const Problem back = io::LoadProblemFile(file);
  const StepProblem step{back.model.get(), ZeroState(*back.model),
                         StepConstraint::FixedLoad(back.load), back.scales};
  StepPoint point;
  point.du = state.u;
  point.r = state.r;
  point.dlambda = back.load;
  return Judge(step, point, 1e-8).verified;
}

class FclibExport : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!io::FclibAvailable()) GTEST_SKIP() << "built without HDF5";
  }
};

TEST_F(FclibExport, AFixedLoadProblemCarriesItsVerifiedAnswer) {
  const auto file = (TempDir("block") / "block.hdf5").string();
  const auto out = RunContactbench("export --problem block --set n=4 --format fclib --out " + file);
  ASSERT_EQ(out.status, 0) << out.output;
  const io::FclibAnswers answers = io::LoadFclibAnswers(file);
  ASSERT_TRUE(answers.has_solution);
  EXPECT_TRUE(answers.guesses.empty());
  EXPECT_TRUE(VerifiedOnTheFile(file, answers.solution));
}

// The Q4 block of examples/ held at a corner and loaded along an arc-length path: step 3 is
// written at its load with its answer, and step 2's state (the same path, traced here) is the
// guess; `run --start guess:1` on the file starts from it and is verified.
TEST_F(FclibExport, APathStepCarriesThePreviousStateAsItsGuess) {
  const auto dir = TempDir("path");
  std::ifstream in(::cb::testing_support::SourceRoot() / "examples/q4-block-on-floor.json");
  nlohmann::json spec = nlohmann::json::parse(in);
  spec["name"] = "q4-path";
  spec["analysis"] = "arc-length";
  spec.erase("load");
  spec["arc_length"] = 0.5;
  spec["steps"] = 4;
  spec["supports"] = nlohmann::json::array({{{"node", 1}, {"fixed", {"x", "y"}}}});
  spec["contact_pairs"].erase(0);  // node 1 is held: its pair would be redundant
  const auto json_file = (dir / "q4-path.json").string();
  std::ofstream(json_file) << spec.dump();

  const auto file = (dir / "step3.hdf5").string();
  const auto out = RunContactbench("export --problem-file " + json_file +
                                   " --format fclib --step 3 --out " + file);
  ASSERT_EQ(out.status, 0) << out.output;
  const io::FclibAnswers answers = io::LoadFclibAnswers(file);
  ASSERT_TRUE(answers.has_solution);
  ASSERT_EQ(answers.guesses.size(), 1u);
  EXPECT_TRUE(VerifiedOnTheFile(file, answers.solution));

  const Problem path = io::LoadProblemFile(json_file);
  PathOptions options = DefaultPathOptions(path);
  options.max_steps = 2;
  struct Accepted final : PathObserver {
    void OnAttempt(const StepAttempt& a) override {
      if (a.accepted) states.push_back(a.state);
    }
    std::vector<State> states;
  } accepted;
  const auto formulation = MakeFormulation("implicit-fb", FormulationConfig());
  TraceProblem(path, *formulation, options, &accepted);
  ASSERT_EQ(accepted.states.size(), 2u);
  const State& second = accepted.states[1];
  EXPECT_LE((answers.guesses[0].u - second.u).lpNorm<Eigen::Infinity>(),
            1e-12 * second.u.lpNorm<Eigen::Infinity>());
  EXPECT_LE((answers.guesses[0].r - second.r).lpNorm<Eigen::Infinity>(),
            1e-12 * second.r.lpNorm<Eigen::Infinity>());
  EXPECT_GT((answers.solution.u - second.u).norm(), 0.0);  // step 3 is further along

  const auto run =
      RunContactbench("run --problem-file " + file +
                      " --formulation active-set --start guess:1 --out " + (dir / "run").string());
  EXPECT_EQ(run.status, 0) << run.output;
}

TEST_F(FclibExport, StepIsRefusedWhereItDoesNotFit) {
  const auto dir = TempDir("refused");
  const auto fixed = RunContactbench(
      "export --problem block --set n=3 --format fclib --step 2 "
      "--out " +
      (dir / "b.hdf5").string());
  EXPECT_EQ(fixed.status, 2) << fixed.output;
  EXPECT_NE(fixed.output.find("fixed-load problem"), std::string::npos) << fixed.output;
  const auto json = RunContactbench("export --problem block --set n=3 --step 2 --out " +
                                    (dir / "b.json").string());
  EXPECT_EQ(json.status, 2) << json.output;
  EXPECT_NE(json.output.find("only with --format fclib"), std::string::npos) << json.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "b.hdf5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "b.json"));
}

}  // namespace
}  // namespace cb
