// The suite driver end to end: exit statuses, messages and the records it writes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr
};

Outcome RunCli(const std::string& arguments) {
  const std::string command = std::string(CONTACTBENCH_BINARY) + " " + arguments + " 2>&1";
  Outcome out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof(buffer), pipe) != nullptr) out.output += buffer;
  const int raw = pclose(pipe);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_cli_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

std::vector<std::string> Lines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(CliTest, ListNamesProblemsFormulationsAndSolvers) {
  const Outcome o = RunCli("list");
  EXPECT_EQ(o.status, 0);
  for (const char* name : {"block", "arch-flat", "arch-curved", "implicit-fb", "newton", "dogleg",
                           "quasi-newton", "length_scale"}) {
    EXPECT_NE(o.output.find(name), std::string::npos) << name;
  }
}

TEST(CliTest, BadArgumentsExitWithStatus2AndListTheChoices) {
  const auto dir = TempDir("bad").string();
  struct Case {
    std::string args;
    std::string expected;
  } cases[] = {
      {"run --problem nope --formulation implicit-fb --out " + dir, "arch-curved"},
      {"run --problem two-bar --formulation nope --out " + dir, "implicit-fb"},
      {"run --problem two-bar --formulation implicit-fb --solver nope --out " + dir, "dogleg"},
      {"run --problem two-bar --formulation implicit-fb --eta 7 --out " + dir, "--eta"},
      {"run --problem two-bar --formulation implicit-fb --steps 0 --out " + dir, "--steps"},
      {"run --problem two-bar --formulation implicit-fb --arc-length -1 --out " + dir,
       "--arc-length"},
      {"run --problem two-bar --formulation implicit-fb --tol 0 --out " + dir, "--tol"},
      {"run --problem two-bar --formulation implicit-fb --start lukewarm --out " + dir,
       "warm, cold"},
      {"run --problem two-bar --formulation implicit-fb --set height --out " + dir, "KEY=VALUE"},
      {"run --problem two-bar --formulation implicit-fb --set heigth=1 --out " + dir, "height"},
      {"run --problem two-bar --formulation implicit-fb --bogus --out " + dir, "--bogus"},
      {"run --problem two-bar --formulation implicit-fb", "--out"},
      {"frobnicate", "list, run"},
  };
  for (const auto& c : cases) {
    const Outcome o = RunCli(c.args);
    EXPECT_EQ(o.status, 2) << c.args << "\n" << o.output;
    EXPECT_NE(o.output.find(c.expected), std::string::npos) << c.args << "\n" << o.output;
  }
}

TEST(CliTest, UnwritableOutputIsRefusedBeforeWork) {
  const Outcome o = RunCli("run --problem two-bar --formulation implicit-fb --out /proc/nope");
  EXPECT_EQ(o.status, 2) << o.output;
}

TEST(CliTest, RunWritesTheFiveRecordFiles) {
  const auto dir = TempDir("run");
  const Outcome o = RunCli(
      "run --problem two-bar-obstacle --formulation implicit-fb --steps 60 "
      "--arc-length 0.02 --out " +
      dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto steps = Lines(dir / "steps.csv");
  // One row per attempt: 60 accepted steps, plus any cut-back attempts near the contact corner.
  int accepted = 0;
  for (std::size_t i = 1; i < steps.size(); ++i) {
    if (steps[i].find(",true,false,arc-length,") != std::string::npos) ++accepted;
  }
  EXPECT_EQ(accepted, 60);
  EXPECT_EQ(steps[0].rfind("problem,formulation,solver,start,step,lambda,control_disp,iterations,"
                           "residual_evals,jacobian_evals,linear_solves,time_s,found,verified,"
                           "eq_res,comp_res,feas_res,step_res,n_contact,kink",
                           0),
            0u)
      << steps[0];
  EXPECT_EQ(steps[1].rfind("two-bar-obstacle,implicit-fb,newton,warm,1,", 0), 0u) << steps[1];
  EXPECT_GT(Lines(dir / "iterations.csv").size(), 61u);
  EXPECT_EQ(Lines(dir / "kinks.csv").size(), 2u);     // header + the one contact change
  EXPECT_EQ(Lines(dir / "solution.csv").size(), 4u);  // header + 3 nodes
  EXPECT_EQ(Lines(dir / "contacts.csv").size(), 2u);
}

TEST(CliTest, AFailedRunExitsWith3AndKeepsItsRecords) {
  const auto dir = TempDir("fail");
  // A verdict tolerance no double can meet: every step fails, the run stops.
  const Outcome o = RunCli(
      "run --problem two-bar --formulation implicit-fb --steps 5 "
      "--tol 1e-300 --max-cutbacks 1 --out " +
      dir.string());
  EXPECT_EQ(o.status, 3) << o.output;
  const auto steps = Lines(dir / "steps.csv");
  ASSERT_EQ(steps.size(), 3u);  // header + two failed attempts
  EXPECT_NE(steps[1].find(",false,"), std::string::npos);
}

TEST(CliTest, CompareReplaysTheSameStepsForEveryFormulationAndStart) {
  const auto dir = TempDir("compare");
  const Outcome o = RunCli(
      "compare --problem two-bar-obstacle --formulations implicit-fb "
      "--starts warm,cold --solver newton --steps 40 --arc-length 0.02 "
      "--out " +
      dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto steps = Lines(dir / "steps.csv");
  // One attempt per reference step for each start, labelled replay.
  int warm = 0, cold = 0;
  for (std::size_t i = 1; i < steps.size(); ++i) {
    EXPECT_NE(steps[i].find(",replay,"), std::string::npos) << steps[i];
    if (steps[i].rfind("two-bar-obstacle,implicit-fb,newton,warm,", 0) == 0) ++warm;
    if (steps[i].rfind("two-bar-obstacle,implicit-fb,newton,cold,", 0) == 0) ++cold;
  }
  EXPECT_EQ(warm, 40);
  EXPECT_EQ(cold, 40);
  const auto runs = Lines(dir / "runs.csv");
  ASSERT_EQ(runs.size(), 3u);  // header + warm + cold
  EXPECT_NE(runs[1].find(",warm,replay,"), std::string::npos) << runs[1];
  // Warm replay of the implicit formulation's own reference verifies every step.
  EXPECT_NE(runs[1].find(",converged,40,40,"), std::string::npos) << runs[1];
  EXPECT_EQ(Lines(dir / "kinks.csv").size(), 2u);  // the reference path's contact change
}

TEST(CliTest, CompareRefusesUnprefixedOptionsAndUnknownFormulations) {
  const auto dir = TempDir("compare_bad").string();
  EXPECT_EQ(RunCli("compare --problem two-bar --option rho_min=1e-3 --out " + dir).status, 2);
  EXPECT_EQ(RunCli("compare --problem two-bar --formulations nope --out " + dir).status, 2);
  EXPECT_EQ(RunCli("compare --problem two-bar --option nope:a=1 --out " + dir).status, 2);
  EXPECT_EQ(RunCli("compare --problem two-bar --mode sideways --out " + dir).status, 2);
}

TEST(CliTest, BlockRunsTheFixedLoadSolve) {
  const auto dir = TempDir("block");
  const Outcome o = RunCli(
      "run --problem block --formulation implicit-fb --start cold "
      "--set n=8 --out " +
      dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto steps = Lines(dir / "steps.csv");
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_NE(steps[1].find(",cold,1,1,"), std::string::npos) << steps[1];
}

}  // namespace
