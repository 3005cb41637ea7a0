// The library traces a problem as the command line does: the same default options, the same
// loading.
#include "problems/problem_path.h"

#include <gtest/gtest.h>

#include "formulations/registry.h"
#include "harness/options.h"

namespace {

TEST(ProblemPathTest, DefaultOptionsAreTheProblemsThetaAndStepsWithDetection) {
  const cb::Problem problem =
      cb::MakeProblem("arch-flat", {{"steps", "37"}, {"arc_length", "0.25"}});
  const cb::PathOptions options = cb::DefaultPathOptions(problem);
  EXPECT_EQ(options.arc_length, 0.25);  // not PathOptions' 0.1 and 100
  EXPECT_EQ(options.max_steps, 37);
  EXPECT_EQ(options.arc_length, problem.arc_length);
  EXPECT_EQ(options.max_steps, problem.steps);
  EXPECT_EQ(options.bifurcations, cb::BifurcationMode::kDetect);
  EXPECT_TRUE(options.locate_kinks);
  EXPECT_TRUE(options.IsValid(nullptr));
}

TEST(ProblemPathTest, TheCommandLinesDefaultsAreTheLibrarys) {
  const cb::Problem problem = cb::MakeProblem("two-bar");
  const cb::PathOptions library = cb::DefaultPathOptions(problem);
  const cb::harness::RunArguments cli = cb::harness::ParseArguments(
      cb::harness::kRun, {"--problem", "two-bar", "--formulation", "implicit-fb", "--out", "x"});
  EXPECT_EQ(cli.tolerance, library.tolerance);
  EXPECT_EQ(cli.max_cutbacks, library.max_cutbacks);
  EXPECT_EQ(cli.locate_kinks, library.locate_kinks);
  EXPECT_EQ(cli.bifurcations, library.bifurcations);
  EXPECT_EQ(cli.start, library.start);
  EXPECT_FALSE(cli.steps.has_value());  // the problem's, as in the library
  EXPECT_FALSE(cli.arc_length.has_value());
}

TEST(ProblemPathTest, TraceProblemRunsTheFixedLoadSolveOrThePath) {
  auto formulation = cb::MakeFormulation("implicit-fb", cb::FormulationConfig());
  const cb::Problem block = cb::MakeProblem("block", {{"n", "4"}});
  const cb::PathSummary solve =
      cb::TraceProblem(block, *formulation, cb::DefaultPathOptions(block));
  EXPECT_EQ(solve.status, cb::Status::kConverged) << solve.message;
  EXPECT_EQ(solve.attempts, 1);
  EXPECT_EQ(solve.final_state.lambda, block.load);

  const cb::Problem bar = cb::MakeProblem("bar-wall");
  const cb::PathSummary path = cb::TraceProblem(bar, *formulation, cb::DefaultPathOptions(bar));
  EXPECT_EQ(path.status, cb::Status::kConverged) << path.message;
  EXPECT_EQ(path.accepted_steps, bar.steps);
}

}  // namespace
