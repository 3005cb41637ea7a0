// The suite driver end to end: exit statuses, messages and the records it writes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "harness/options.h"
#include "record_table.h"
#include "refusal.h"
#include "run_contactbench.h"
#include "source_tree.h"
#include "step/formulation.h"

namespace {

using Outcome = ::cb::testing_support::CliOutcome;
using ::cb::testing_support::At;
using ::cb::testing_support::Refusal;
using ::cb::testing_support::RefusalLine;
using ::cb::testing_support::RefusedAt;
using ::cb::testing_support::RefusedOption;
using ::cb::testing_support::RunShell;

// stdout and stderr.
Outcome RunCli(const std::string& arguments) {
  return ::cb::testing_support::RunContactbench(arguments);
}

// Only stdout: the help and the usage are printed there.
Outcome RunCliStdout(const std::string& arguments) {
  return ::cb::testing_support::RunContactbench(arguments, "2>/dev/null");
}

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_cli_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

using ::cb::testing_support::Lines;

TEST(CliTest, ListNamesProblemsFormulationsAndSolvers) {
  const Outcome o = RunCli("list");
  EXPECT_EQ(o.status, 0);
  for (const char* name : {"block", "arch-flat", "arch-curved", "implicit-fb", "newton", "dogleg",
                           "quasi-newton", "length_scale"}) {
    EXPECT_NE(o.output.find(name), std::string::npos) << name;
  }
}

using cb::harness::NameAndValue;

// The option names that start the lines of a --help's option list.
std::set<std::string> ListedOptions(const std::string& help) {
  std::set<std::string> names;
  std::istringstream in(help.substr(help.find("\noptions:\n")));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("  --", 0) == 0) names.insert(line.substr(2, line.find(' ', 2) - 2));
  }
  return names;
}

TEST(CliTest, EveryCommandsHelpListsExactlyItsOptionsAndExits0) {
  for (const auto& command : cb::harness::Commands()) {
    const Outcome o = RunCliStdout(std::string(command.name) + " --help");
    EXPECT_EQ(o.status, 0) << command.name << "\n" << o.output;
    EXPECT_EQ(o.output.rfind(std::string("usage: contactbench ") + command.name, 0), 0u)
        << o.output;
    std::set<std::string> expected;
    for (const auto& option : cb::harness::Options()) {
      if ((option.commands & command.command) == 0) continue;
      expected.insert(option.name);
      EXPECT_NE(o.output.find(NameAndValue(option)), std::string::npos)
          << command.name << " --help lacks " << NameAndValue(option) << "\n"
          << o.output;
    }
    EXPECT_EQ(ListedOptions(o.output), expected) << command.name << "\n" << o.output;
  }
  // --help wins over the missing required options.
  EXPECT_EQ(RunCliStdout("run --problem two-bar --help").status, 0);
}

TEST(CliTest, TheUsageShowsEveryCommandAndEveryOption) {
  for (const char* args : {"help", "--help"}) {
    const Outcome o = RunCliStdout(args);
    EXPECT_EQ(o.status, 0) << o.output;
    for (const auto& command : cb::harness::Commands()) {
      EXPECT_NE(o.output.find(std::string("contactbench ") + command.name + " "), std::string::npos)
          << command.name;
    }
    for (const auto& option : cb::harness::Options()) {
      EXPECT_NE(o.output.find(NameAndValue(option)), std::string::npos) << NameAndValue(option);
    }
  }
  EXPECT_EQ(RunCliStdout("").status, 2);  // no command: the usage, and status 2
}

TEST(CliTest, OptionsOfAnotherCommandAreRefused) {
  const auto dir = TempDir("other_command").string();
  // The command refuses the other command's option, naming it (and, for --starts, --start).
  struct Case {
    std::string args;
    Refusal expected;
  } cases[] = {
      {"run --problem two-bar --formulation implicit-fb --starts cold --out " + dir,
       At("run", {"'--starts'", "--start,"})},
      {"compare --problem two-bar --formulation implicit-fb --out " + dir,
       At("compare", {"'--formulation'"})},
      {"compare --problem two-bar --save-every 3 --out " + dir, At("compare", {"'--save-every'"})},
      {"list --steps 3", At("list", {"'--steps'"})},
      {"run --problem two-bar --formulation implicit-fb --no-kinks --no-kinks --out " + dir,
       At("--no-kinks")},
      {"run --problem two-bar --formulation implicit-fb --out", At("--out")},
  };
  for (const auto& c : cases) {
    const Outcome o = RunCli(c.args);
    EXPECT_EQ(o.status, 2) << c.args << "\n" << o.output;
    EXPECT_TRUE(RefusedOption(o.output, c.expected)) << c.args;
  }
}

TEST(CliTest, BadArgumentsExitWithStatus2AndListTheChoices) {
  const auto dir = TempDir("bad").string();
  // The option, the bad value and, for a name, the valid choices.
  struct Case {
    std::string args;
    Refusal expected;
  } cases[] = {
      {"run --problem nope --formulation implicit-fb --out " + dir,
       At("--problem", {"'nope'", "arch-curved", "two-bar-obstacle"})},
      {"run --problem two-bar --formulation nope --out " + dir,
       At("--formulation", {"'nope'", "implicit-fb", "active-set"})},
      {"run --problem two-bar --formulation implicit-fb --solver nope --out " + dir,
       At("--solver", {"'nope'", "newton", "dogleg"})},
      {"run --problem two-bar --formulation implicit-fb --eta 7 --out " + dir, At("--eta", {"7"})},
      {"run --problem two-bar --formulation implicit-fb --steps 0 --out " + dir, At("--steps")},
      {"run --problem two-bar --formulation implicit-fb --arc-length -1 --out " + dir,
       At("--arc-length")},
      {"run --problem two-bar --formulation implicit-fb --tol 0 --out " + dir, At("--tol")},
      {"run --problem two-bar --formulation implicit-fb --start lukewarm --out " + dir,
       At("--start", {"'lukewarm'", "warm", "cold", "near"})},
      {"run --problem two-bar --formulation implicit-fb --set height --out " + dir,
       At("--set", {"KEY=VALUE", "'height'"})},
      {"run --problem two-bar --formulation implicit-fb --set heigth=1 --out " + dir,
       At("problem", {"'two-bar'", "'heigth'", "'height'"})},
      {"run --problem two-bar --formulation implicit-fb --bogus --out " + dir,
       At("run", {"'--bogus'"})},
      {"run --problem two-bar --formulation implicit-fb", At("--out")},
      {"frobnicate", At("", {"'frobnicate'", "list", "run", "compare"})},
  };
  for (const auto& c : cases) {
    const Outcome o = RunCli(c.args);
    EXPECT_EQ(o.status, 2) << c.args << "\n" << o.output;
    EXPECT_TRUE(RefusedOption(o.output, c.expected)) << c.args;
  }
}

TEST(CliTest, UnwritableOutputIsRefusedBeforeWork) {
  // /proc refuses new entries even to root; a regular file cannot hold a directory.
  const auto dir = TempDir("unwritable");
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "a-file").string();
  std::ofstream(file) << "x";
  for (const std::string& out : {std::string("/proc/nope"), file + "/sub", file}) {
    for (const std::string& command :
         {"run --problem two-bar --formulation implicit-fb --out " + out,
          "compare --problem two-bar --formulations implicit-fb --out " + out,
          "export --problem two-bar --out " + out + "/p.json"}) {
      const Outcome o = RunCli(command);
      EXPECT_EQ(o.status, 2) << command << "\n" << o.output;
      // The message names the directory; nothing ran (no solver summary was printed).
      EXPECT_NE(o.output.find("--out"), std::string::npos) << command << "\n" << o.output;
      EXPECT_NE(o.output.find(out), std::string::npos) << command << "\n" << o.output;
      EXPECT_EQ(o.output.find("accepted steps"), std::string::npos) << o.output;
    }
  }
}

TEST(CliTest, OutOfRangeAndRepeatedOptionsAreRefused) {
  const auto dir = TempDir("range").string();
  std::filesystem::create_directories(dir);  // for export's "is a directory"
  const std::string run = "run --problem two-bar --formulation implicit-fb --out " + dir + " ";
  // The option and the value refused, as typed (a bad number is not read as another one).
  struct Case {
    std::string args;
    Refusal expected;
  } cases[] = {
      {run + "--steps 1e20", At("--steps", {"'1e20'"})},
      {run + "--steps -3", At("--steps")},
      {run + "--arc-length inf", At("--arc-length", {"'inf'"})},
      {run + "--arc-length 0", At("--arc-length")},
      {run + "--tol nan", At("--tol", {"'nan'"})},
      // It would "verify" anything: refused with the largest allowed, the verdict's range.
      {run + "--tol 1e8", At("--tol", {"0.0001", "'1e8'"})},
      {run + "--tol 1e300", At("--tol", {"0.0001", "'1e300'"})},
      {run + "--tol 2e-4", At("--tol", {"0.0001", "'2e-4'"})},
      {run + "--time-limit -1", At("--time-limit")},
      {run + "--max-cutbacks -1", At("--max-cutbacks")},
      {run + "--eta 2.5", At("--eta", {"'2.5'"})},
      {run + "--steps 5 --steps 6", At("--steps")},
      {run + "--steps 0x10", At("--steps", {"'0x10'"})},
      {run + "--steps 1e1", At("--steps", {"'1e1'"})},
      {run + "--arc-length 0x1p-3", At("--arc-length", {"'0x1p-3'"})},
      {run + "--arc-length 1e-320", At("--arc-length", {"'1e-320'"})},
      {run + "--arc-length 1e-400", At("--arc-length", {"'1e-400'"})},
      {run + "--arc-length 1e400", At("--arc-length", {"'1e400'"})},
      {"run --problem block --formulation implicit-fb --set n=4 --set n=6 --out " + dir,
       At("--set", {"'n'"})},
      {"compare --problem two-bar --formulations , --out " + dir, At("--formulations", {"','"})},
      {"compare --problem two-bar --formulations implicit-fb,,active-set --out " + dir,
       At("--formulations", {"'implicit-fb,,active-set'"})},
      {"compare --problem two-bar --starts , --out " + dir, At("--starts", {"','"})},
      // Without Ipopt in the build: "ipopt-energy: this build has no Ipopt", also status 2.
      {"compare --problem two-bar --reference ipopt-energy --out " + dir, At("", {"ipopt-energy"})},
      {run + "--problem-file x.json", At("", {"--problem", "--problem-file"})},
      {"run --formulation implicit-fb --out " + dir, At("", {"--problem", "--problem-file"})},
      {"export --problem two-bar", At("--out")},
      {"export --problem two-bar --formulation implicit-fb --out " + dir + "/p.json",
       At("export", {"'--formulation'"})},
      {"export --problem nope --out " + dir + "/p.json",
       At("--problem", {"'nope'", "arch-curved"})},
      {"export --problem two-bar --out " + dir, At("--out", {"'" + dir + "'"})},
  };
  for (const auto& c : cases) {
    const Outcome o = RunCli(c.args);
    EXPECT_EQ(o.status, 2) << c.args << "\n" << o.output;
    EXPECT_TRUE(RefusedOption(o.output, c.expected)) << c.args;
  }
}

// --- problem files ---------------------------------------------------------------------------

const std::filesystem::path kExamples = ::cb::testing_support::SourceRoot() / "examples";

using ::cb::testing_support::Table;

double Number(const std::map<std::string, std::string>& row, const std::string& column) {
  auto it = row.find(column);
  return it == row.end() ? std::nan("") : std::stod(it->second);
}

TEST(CliTest, EveryExampleRunsAndVerifiesWithItsKnownAnswer) {
  struct Case {
    std::string file;
    std::function<void(const std::filesystem::path&)> check;
  } cases[] = {
      {"truss-2d-bar-wall.json",
       [](const std::filesystem::path& out) {
         // k = 1 / (L1/EA1 + L2/EA2) = 200/3; past lambda_c = k gap the wall carries the rest.
         const auto contacts = Table(out / "contacts.csv");
         ASSERT_EQ(contacts.size(), 1u);
         const double lambda = Number(contacts[0], "lambda");
         EXPECT_GT(lambda, 200.0 / 3.0 * 0.01);
         EXPECT_NEAR(Number(contacts[0], "g"), 0.0, 1e-10);
         EXPECT_NEAR(Number(contacts[0], "r"), -(lambda - 200.0 / 3.0 * 0.01), 1e-8);
         const auto nodes = Table(out / "solution.csv");
         EXPECT_NEAR(Number(nodes[1], "ux"), 200.0 / 3.0 * 0.01 * 0.005, 1e-10);  // N L1 / EA1
       }},
      {"truss-3d-tripod.json",
       [](const std::filesystem::path& out) {
         // On the sphere's top at z = 0.7: r = -(lambda - 3 EA w (1/l - 1/L)) P at w = 0.7.
         const double l = std::sqrt(1.0 + 0.49), length = std::sqrt(2.0);
         const double lambda_c = 3.0 * 10.0 * 0.7 * (1.0 / l - 1.0 / length);
         const auto contacts = Table(out / "contacts.csv");
         ASSERT_EQ(contacts.size(), 1u);
         const double lambda = Number(contacts[0], "lambda");
         EXPECT_GT(lambda, lambda_c);
         EXPECT_NEAR(Number(contacts[0], "r"), -(lambda - lambda_c), 1e-8);
         const auto nodes = Table(out / "solution.csv");
         EXPECT_NEAR(Number(nodes[0], "uz"), -0.3, 1e-10);
         EXPECT_NEAR(Number(nodes[0], "ux"), 0.0, 1e-10);
       }},
      {"q4-block-on-floor.json",
       [](const std::filesystem::path& out) {
         // Uniaxial stress -10: uy = -10 y / 1000, ux = 0.25 * 10 x / 1000 (x fixed at x = 0).
         for (const auto& row : Table(out / "solution.csv")) {
           EXPECT_NEAR(Number(row, "uy"), -0.01 * Number(row, "y"), 1e-12);
           EXPECT_NEAR(Number(row, "ux"), 0.0025 * Number(row, "x"), 1e-12);
         }
         double total = 0.0;  // the floor carries p * width * thickness = 2
         for (const auto& row : Table(out / "contacts.csv")) total += Number(row, "r");
         EXPECT_NEAR(total, -2.0, 1e-10);
       }},
      {"q4-block-gmsh.json",
       [](const std::filesystem::path& out) {
         const auto rows = Table(out / "solution.csv");
         EXPECT_EQ(rows.size(), 6u);
         for (const auto& row : rows) {
           EXPECT_NEAR(Number(row, "uy"), -0.01 * Number(row, "y"), 1e-12);
           EXPECT_NEAR(Number(row, "ux"), 0.0025 * Number(row, "x"), 1e-12);
         }
       }},
      {"lcp-dense-2x2.json",
       [](const std::filesystem::path& out) {
         const auto rows = Table(out / "solution.csv");
         ASSERT_EQ(rows.size(), 2u);
         EXPECT_NEAR(Number(rows[0], "z"), 4.0 / 3.0, 1e-8);
         EXPECT_NEAR(Number(rows[1], "z"), 7.0 / 3.0, 1e-8);
       }},
      {"lcp-sparse-4x4.json",
       [](const std::filesystem::path& out) {
         const auto rows = Table(out / "solution.csv");
         ASSERT_EQ(rows.size(), 4u);
         const double z[4] = {2.8, 0.0, 0.8, 1.2}, w[4] = {0.0, 0.4, 0.0, 0.0};
         for (int i = 0; i < 4; ++i) {
           EXPECT_NEAR(Number(rows[i], "z"), z[i], 1e-8) << i;
           EXPECT_NEAR(Number(rows[i], "w"), w[i], 1e-8) << i;
         }
       }},
  };
  for (const auto& c : cases) {
    for (const char* formulation : {"implicit-fb", "active-set"}) {
      const auto out = TempDir("example_" + std::string(formulation) + "_" + c.file);
      const Outcome o = RunCli("run --problem-file " + (kExamples / c.file).string() +
                               " --formulation " + formulation + " --out " + out.string());
      ASSERT_EQ(o.status, 0) << c.file << " " << formulation << "\n" << o.output;
      for (const auto& row : Table(out / "steps.csv")) {
        if (row.at("accepted") == "true") {
          EXPECT_EQ(row.at("verified"), "true");
        }
      }
      SCOPED_TRACE(c.file + " " + formulation);
      c.check(out);
    }
  }
}

// `--out /` is refused as root too, before anything is made there (issue 30: it was accepted,
// and `--overwrite` would have removed /figures and /vtk). Made safe: the run sees / read-only
// (a mount namespace of its own), so a run that took / could write nothing into it; and the
// refusal must be the root directory's, given before the directory is created or probed (a
// read-only directory is refused too, for not being writable).
TEST(CliTest, TheRootDirectoryIsRefusedAsOutBeforeAnythingIsMadeThere) {
  if (geteuid() != 0) GTEST_SKIP() << "the point is a run as root";
  const std::string read_only_root =
      "unshare -m sh -c 'mount --bind / / && "
      "mount -o remount,bind,ro / && exec \"$0\" \"$@\"' ";
  if (RunShell(read_only_root + "true 2>&1").status != 0) {
    GTEST_SKIP() << "no mount namespace with a read-only root here";
  }
  const Outcome o = RunShell(read_only_root + CONTACTBENCH_BINARY +
                             " run --problem two-bar --formulation implicit-fb --out / 2>&1");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_TRUE(RefusedOption(o.output, At("--out", {"root"}))) << o.output;
  EXPECT_EQ(o.output.find("writable"), std::string::npos) << "probed / first: " << o.output;
  EXPECT_EQ(o.output.find("cannot create"), std::string::npos) << o.output;
}

TEST(CliTest, BadProblemFilesExitWith2NamingFileAndField) {
  const auto dir = TempDir("bad_files");
  std::filesystem::create_directories(dir);
  struct Case {
    std::string name;
    std::string text;
    Refusal expected;  // in the file c.name
  } cases[] = {
      {"malformed.json", "{\n\"kind\": \"lcp\",\n\"M\": [[1]] \"q\": [1]}", At("", {"line 3"})},
      {"negative.json",
       R"({"kind": "truss", "dimension": 2, "nodes": [{"id": 1, "x": [0, 0]},
           {"id": 2, "x": [1, 0]}], "members": [{"nodes": [1, 2], "E": -1, "A": 1}],
           "supports": [{"node": 1, "fixed": ["x", "y"]}, {"node": 2, "fixed": ["y"]}],
           "length_scale": 1, "force_scale": 1, "analysis": "fixed-load"})",
       At("/members/0/E", {"-1"})},
      {"lcp.json", R"({"kind": "lcp", "M": [[1, 0], [0, 1]], "q": [1]})",
       At("/q", {"1", "M", "2"})},
      // The length scale an LCP's data imply (max |q| over the largest row sum of |M|)
      // overflows, then underflows: both were an internal error, exit 3 (issue 30).
      {"overflowing-scale.json",
       R"({"kind": "lcp", "M": [[1e-300, 0], [0, 1e-300]], "q": [-1e300, 1]})",
       At("", {"length_scale"})},
      {"underflowing-scale.json",
       R"({"kind": "lcp", "M": [[1e300, 0], [0, 1e300]], "q": [-1e-300, 1e-300]})",
       At("", {"length_scale"})},
      {"missing.json", "", At("")},
  };
  for (const auto& c : cases) {
    const auto path = dir / c.name;
    if (!c.text.empty()) std::ofstream(path) << c.text;
    const Outcome o = RunCli("run --problem-file " + path.string() +
                             " --formulation implicit-fb --out " + (dir / "out").string());
    EXPECT_EQ(o.status, 2) << c.name << "\n" << o.output;
    EXPECT_TRUE(RefusedAt(RefusalLine(o.output), path.string(), c.expected)) << c.name;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "work started for " << c.name;
  }
}

TEST(CliTest, AnExportedProblemTracesTheSamePathAsTheNamedProblem) {
  const auto dir = TempDir("export");
  const std::string file = (dir / "p.json").string();
  const Outcome e = RunCli("export --problem two-bar-obstacle --set height=0.4 --out " + file);
  ASSERT_EQ(e.status, 0) << e.output;
  const std::string tail = " --formulation implicit-fb --steps 30 --arc-length 0.02 --out ";
  const Outcome a =
      RunCli("run --problem two-bar-obstacle --set height=0.4" + tail + (dir / "a").string());
  const Outcome b = RunCli("run --problem-file " + file + tail + (dir / "b").string());
  ASSERT_EQ(a.status, 0) << a.output;
  ASSERT_EQ(b.status, 0) << b.output;
  const auto ra = Table(dir / "a" / "steps.csv");
  const auto rb = Table(dir / "b" / "steps.csv");
  ASSERT_EQ(ra.size(), rb.size());
  for (std::size_t i = 0; i < ra.size(); ++i) {
    for (const char* column : {"lambda", "control_disp", "iterations", "n_contact"}) {
      EXPECT_EQ(ra[i].at(column), rb[i].at(column)) << "row " << i << " " << column;
    }
  }
  // --set reaches a problem file's run parameters too.
  const Outcome s = RunCli("run --problem-file " + file + " --set steps=3" +
                           " --formulation implicit-fb --out " + (dir / "c").string());
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_EQ(Table(dir / "c" / "steps.csv").size(), 3u);
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
                           "eq_res,comp_res,feas_res,step_res,fclib_error,n_contact,kink",
                           0),
            0u)
      << steps[0];
  EXPECT_EQ(steps[1].rfind("two-bar-obstacle,implicit-fb,newton,warm,1,", 0), 0u) << steps[1];
  EXPECT_GT(Lines(dir / "iterations.csv").size(), 61u);
  EXPECT_EQ(Lines(dir / "kinks.csv").size(), 2u);     // header + the one contact change
  EXPECT_EQ(Lines(dir / "solution.csv").size(), 4u);  // header + 3 nodes
  EXPECT_EQ(Lines(dir / "contacts.csv").size(), 2u);
}

// Every attempt records the tolerance it was judged to, so a record says how strict its
// "verified" is.
TEST(CliTest, StepsRecordTheVerdictsTolerance) {
  const auto dir = TempDir("tolerance");
  const Outcome o = RunCli(
      "run --problem two-bar --formulation implicit-fb --steps 3 --tol 1e-4 --out " + dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto rows = Table(dir / "steps.csv");
  ASSERT_FALSE(rows.empty());
  for (const auto& row : rows) EXPECT_EQ(Number(row, "tolerance"), 1e-4);
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

// A solve that runs out of time is a failed step: cut back, recorded as time_limit with the
// reason, and the run ends as failed (3), not as interrupted (4, SIGINT/SIGTERM only).
TEST(CliTest, ATimeLimitFailsTheStepNotTheProcess) {
  const auto dir = TempDir("time_limit");
  const Outcome o = RunCli(
      "run --problem two-bar --formulation implicit-fb --steps 3 --time-limit 1e-9 "
      "--max-cutbacks 1 --out " +
      dir.string());
  EXPECT_EQ(o.status, 3) << o.output;
  // The summary and every attempt give the one reason of every backend (TimeLimitMessage);
  // `time_limit` is the status column's documented word (docs/records.md), the contract.
  const std::string reason = cb::TimeLimitMessage(1e-9);
  EXPECT_NE(o.output.find(reason), std::string::npos) << o.output;
  const auto steps = Table(dir / "steps.csv");
  ASSERT_EQ(steps.size(), 2u) << o.output;  // the attempt and its cut-back
  for (const auto& row : steps) {
    EXPECT_EQ(row.at("status"), "time_limit");
    EXPECT_EQ(row.at("message").rfind(reason, 0), 0u) << row.at("message");
  }
}

// In `compare` a formulation that runs out of time fails its run; the others still run.
TEST(CliTest, ATimeLimitInCompareFailsOneRunAndTheComparisonGoesOn) {
  const auto dir = TempDir("compare_time_limit");
  const Outcome o = RunCli(
      "compare --problem two-bar --formulations implicit-fb,nonsmooth-fb --starts warm,cold "
      "--mode free --steps 2 --time-limit 1e-9 --out " +
      dir.string());
  EXPECT_EQ(o.status, 0) << o.output;
  const auto runs = Lines(dir / "runs.csv");
  ASSERT_EQ(runs.size(), 5u) << o.output;  // header + 2 formulations x 2 starts
  for (std::size_t i = 1; i < runs.size(); ++i) {
    EXPECT_NE(runs[i].find(",failed,"), std::string::npos) << runs[i];  // the outcome column
    // No step accepted, and the reason names the step and the time limit's own reason.
    EXPECT_NE(runs[i].find(",0,step 1 "), std::string::npos) << runs[i];
    EXPECT_NE(runs[i].find(cb::TimeLimitMessage(1e-9)), std::string::npos) << runs[i];
  }
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
  EXPECT_NE(steps[1].find(",cold,1,1.0,"), std::string::npos) << steps[1];
}

}  // namespace

namespace cb {
namespace {

// --save-every writes the saved states as CSV rows and as VTK files that a collection lists:
// the apex of the two-bar truss moved by the same amount in both.
TEST(CliTest, SavedStatesAreWrittenAsCsvAndVtk) {
  const auto dir = std::filesystem::temp_directory_path() / "contactbench_cli_vtk";
  std::filesystem::remove_all(dir);
  const std::string command = std::string(CONTACTBENCH_BINARY) +
                              " run --problem two-bar --formulation implicit-fb --steps 20"
                              " --save-every 10 --out " +
                              dir.string() + " 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  // Steps 10 and 20, the limit point passed in step 10, and the final state.
  std::ifstream pvd(dir / "vtk" / "two-bar.pvd");
  ASSERT_TRUE(pvd.good());
  const std::string collection((std::istreambuf_iterator<char>(pvd)), {});
  for (const char* file :
       {"two-bar_0000.vtu", "two-bar_0001.vtu", "two-bar_0002.vtu", "two-bar_0003.vtu"}) {
    // The final state (0003) replaces the regular save of the same step (0002) in it.
    EXPECT_EQ(collection.find(file) != std::string::npos, std::string(file) != "two-bar_0002.vtu")
        << file;
    EXPECT_TRUE(std::filesystem::exists(dir / "vtk" / file)) << file;
  }
  std::ifstream vtu(dir / "vtk" / "two-bar_0002.vtu");  // step 20
  const std::string grid((std::istreambuf_iterator<char>(vtu)), {});
  EXPECT_NE(grid.find("NumberOfPoints=\"3\" NumberOfCells=\"2\""), std::string::npos);
  // The apex (node 1) displacement of step 20 in the CSV, and in the .vtu's point data.
  double uy = 0.0;
  int rows = 0;
  std::ifstream csv(dir / "snapshots.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "step,label,lambda,node,x,y,ux,uy");
  while (std::getline(csv, line)) {
    ++rows;
    if (line.rfind("20,step,", 0) == 0 && line.find(",1,0.0,0.5,") != std::string::npos) {
      uy = std::stod(line.substr(line.rfind(',') + 1));
    }
  }
  EXPECT_EQ(rows, 12);  // 4 saved states x 3 nodes
  ASSERT_LT(uy, 0.0);
  const auto data = grid.find("Name=\"displacement\"");
  ASSERT_NE(data, std::string::npos);
  std::istringstream values(grid.substr(grid.find('>', data) + 1));
  double v[9];
  for (double& x : v) values >> x;
  EXPECT_DOUBLE_EQ(v[4], uy);  // node 1, y component
}

}  // namespace
}  // namespace cb

namespace {

// --- the records are never lost, truncated or mixed ------------------------------------------

// Whether every file under `dir` with the suffix ".csv" ends with a line break (or is empty).
void ExpectOnlyWholeLines(const std::filesystem::path& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".csv") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    if (!text.empty()) {
      EXPECT_EQ(text.back(), '\n') << entry.path();
    }
  }
}

nlohmann::json RunJsonOf(const std::filesystem::path& dir) {
  std::ifstream in(dir / "run.json");
  return nlohmann::json::parse(in);
}

TEST(CliTest, AFullDiskStopsTheRunWithStatus3NamingTheFile) {
  // A file size limit (unprivileged, inherited by the child) makes the write that crosses it
  // fail part-way, as a full disk does.
  const auto dir = TempDir("full_disk");
  for (const std::string& command :
       {std::string("run --problem arch-flat --formulation implicit-fb --steps 50"),
        std::string("compare --problem arch-flat --formulations implicit-fb --steps 50")}) {
    const auto out = dir / command.substr(0, command.find(' '));
    const Outcome o = RunShell("ulimit -f 10; " + std::string(CONTACTBENCH_BINARY) + " " + command +
                               " --out " + out.string() + " 2>&1");
    EXPECT_EQ(o.status, 3) << command << "\n" << o.output;
    // The refusal names the file it could not write, in the output directory.
    EXPECT_TRUE(RefusedOption(o.output, At("", {"'" + out.string() + "/"}))) << command;
    ExpectOnlyWholeLines(out);
    // run.json is small enough to be written under the limit, and says why the run stopped.
    const auto run = RunJsonOf(out);
    EXPECT_EQ(run.at("exit_status"), 3);
    EXPECT_NE(run.at("reason").get<std::string>().find(out.string() + "/"), std::string::npos)
        << run.dump();
  }
  // A comparison stopped by a failed write records no outcome for steps it could not write.
  EXPECT_FALSE(std::filesystem::exists(dir / "compare" / "runs.csv") &&
               Lines(dir / "compare" / "runs.csv").size() > 1);
}

TEST(CliTest, AnEarlierRunsRecordsAreRefusedUnlessOverwritten) {
  const auto dir = TempDir("overwrite");
  const std::string out = " --out " + dir.string();
  const Outcome first =
      RunCli("run --problem two-bar --formulation implicit-fb --save-every 50" + out);
  ASSERT_EQ(first.status, 0) << first.output;
  ASSERT_TRUE(std::filesystem::exists(dir / "contacts.csv"));
  ASSERT_TRUE(std::filesystem::exists(dir / "vtk"));
  std::ofstream(dir / "notes.txt") << "mine";
  const std::string lcp = "run --problem-file " + (kExamples / "lcp-dense-2x2.json").string() +
                          " --formulation implicit-fb" + out;
  const Outcome refused = RunCli(lcp);
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("--overwrite"), std::string::npos) << refused.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "contacts.csv"));  // untouched
  const Outcome replaced = RunCli(lcp + " --overwrite");
  ASSERT_EQ(replaced.status, 0) << replaced.output;
  // Only the new run's records: an LCP has no contacts.csv and no VTK files.
  EXPECT_FALSE(std::filesystem::exists(dir / "contacts.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "vtk"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cells.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "notes.txt"));  // not a record: kept
  EXPECT_EQ(Lines(dir / "steps.csv")[1].rfind("lcp-dense-2x2,", 0), 0u);
  // A directory holding only other files is not refused.
  const auto other = TempDir("overwrite_other");
  std::filesystem::create_directories(other);
  std::ofstream(other / "notes.txt") << "mine";
  EXPECT_EQ(
      RunCli("run --problem two-bar --formulation implicit-fb --out " + other.string()).status, 0);
}

TEST(CliTest, RunAndCompareWriteRunJson) {
  const auto dir = TempDir("run_json");
  const Outcome r = RunCli(
      "run --problem two-bar --formulation implicit-fb --steps 7 --set height=0.4 "
      "--time-limit 60 --out " +
      (dir / "run").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto run = RunJsonOf(dir / "run");
  EXPECT_FALSE(run.at("version").get<std::string>().empty());
  EXPECT_TRUE(run.contains("commit"));
  EXPECT_EQ(run.at("command"), "run");
  EXPECT_EQ(run.at("command_line").at(1), "run");
  EXPECT_EQ(run.at("command_line").back(), (dir / "run").string());
  EXPECT_EQ(run.at("problem"), "two-bar");
  EXPECT_EQ(run.at("problem_source"), "--problem two-bar");
  EXPECT_EQ(run.at("settings").at("height"), "0.4");
  EXPECT_EQ(run.at("formulations"), nlohmann::json::array({"implicit-fb"}));
  EXPECT_EQ(run.at("starts"), nlohmann::json::array({"warm"}));
  EXPECT_EQ(run.at("tolerance"), 1e-8);
  EXPECT_EQ(run.at("time_limit_s"), 60.0);
  EXPECT_EQ(run.at("exit_status"), 0);
  EXPECT_EQ(run.at("counts").at("accepted_steps"), 7);
  EXPECT_EQ(run.at("counts").at("attempts"),
            static_cast<int>(Lines(dir / "run" / "steps.csv").size()) - 1);
  EXPECT_GE(run.at("wall_time_s").get<double>(), 0.0);
  EXPECT_EQ(run.at("started_at").get<std::string>().size(), 20u);  // 2026-01-02T03:04:05Z

  // A failed run says so, with the path's reason.
  const Outcome f = RunCli(
      "run --problem two-bar --formulation implicit-fb --steps 5 --tol 1e-300 --max-cutbacks 1 "
      "--out " +
      (dir / "failed").string());
  ASSERT_EQ(f.status, 3) << f.output;
  const auto failed = RunJsonOf(dir / "failed");
  EXPECT_EQ(failed.at("exit_status"), 3);
  EXPECT_FALSE(failed.at("reason").get<std::string>().empty());

  const Outcome c = RunCli(
      "compare --problem two-bar --formulations implicit-fb,nonsmooth-fb --starts warm,cold "
      "--steps 5 --out " +
      (dir / "compare").string());
  ASSERT_EQ(c.status, 0) << c.output;
  const auto compare = RunJsonOf(dir / "compare");
  EXPECT_EQ(compare.at("command"), "compare");
  EXPECT_EQ(compare.at("formulations"), nlohmann::json::array({"implicit-fb", "nonsmooth-fb"}));
  EXPECT_EQ(compare.at("starts"), nlohmann::json::array({"warm", "cold"}));
  EXPECT_EQ(compare.at("mode"), "replay");
  EXPECT_EQ(compare.at("reference"), "implicit-fb");
  EXPECT_EQ(compare.at("counts").at("runs"), 4);
  EXPECT_EQ(compare.at("exit_status"), 0);
}

TEST(CliTest, ProblemNamesThatAreNotFileSafeAreRefused) {
  const auto dir = TempDir("names");
  std::filesystem::create_directories(dir);
  for (const char* name : {"../../escaped", "a/b", "say \\\"hi\\\"", ".hidden", ""}) {
    const auto file = dir / "p.json";
    std::ofstream(file) << R"({"kind": "lcp", "name": ")" << name
                        << R"(", "M": [[1, 0], [0, 1]], "q": [-1, 1]})";
    const Outcome o =
        RunCli("run --problem-file " + file.string() +
               " --formulation implicit-fb --save-every 1 --out " + (dir / "out").string());
    EXPECT_EQ(o.status, 2) << name << "\n" << o.output;
    EXPECT_TRUE(RefusedAt(RefusalLine(o.output), file.string(), At("/name"))) << name;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.parent_path().parent_path() / "escaped"));
}

TEST(CliTest, InputsThatAreNotRegularFilesAreRefusedAtOnce) {
  const auto dir = TempDir("not_regular");
  std::filesystem::create_directories(dir / "a-directory");
  const std::string fifo = (dir / "a-fifo").string();
  ASSERT_EQ(RunShell("mkfifo " + fifo).status, 0);
  // A mesh path that is a directory.
  std::ofstream(dir / "mesh-dir.json") << R"({"kind": "plane-stress-q4", "thickness": 0.1,
      "material": {"E": 1000.0, "nu": 0.25}, "mesh": {"file": "a-directory"}})";
  struct Case {
    std::string file;
    std::string refused;  // the file refused, and what it is
    std::string kind;
  } cases[] = {
      {"/dev/zero", "/dev/zero", "device"},
      {(dir / "a-directory").string(), (dir / "a-directory").string(), "directory"},
      {fifo, fifo, "FIFO"},
      {(dir / "mesh-dir.json").string(), (dir / "a-directory").string(), "directory"},
  };
  for (const auto& c : cases) {
    // `timeout`: reading /dev/zero or a FIFO without a writer would never end.
    const Outcome o =
        RunShell("timeout 20 " + std::string(CONTACTBENCH_BINARY) + " run --problem-file " +
                 c.file + " --formulation implicit-fb --out " + (dir / "out").string() + " 2>&1");
    EXPECT_EQ(o.status, 2) << c.file << "\n" << o.output;
    EXPECT_TRUE(RefusedAt(RefusalLine(o.output), c.refused, At("", {c.kind}))) << c.file;
  }
}

}  // namespace

// --- memory ------------------------------------------------------------------------------------

namespace {

// A problem whose estimated memory exceeds the limit is refused at once, before it is built
// and before --out is touched; the limit is lowered for the test through the variable that
// replaces the machine's.
TEST(CliTest, AProblemTooLargeForTheMemoryIsRefusedAtOnce) {
  const auto dir = TempDir("memory_refused");
  for (const char* n : {"100", "2000"}) {
    const Outcome o = RunShell("CONTACTBENCH_MEMORY_LIMIT=1e8 " + std::string(CONTACTBENCH_BINARY) +
                               " run --problem block --set n=" + std::string(n) +
                               " --formulation implicit-fb --out " + dir.string() + " 2>&1");
    EXPECT_EQ(o.status, 2) << o.output;
    // The problem, the limit it exceeds and the option that lifts it.
    EXPECT_TRUE(RefusedOption(
        o.output, At("--problem", {"block", "CONTACTBENCH_MEMORY_LIMIT", "--allow-memory"})));
    EXPECT_FALSE(std::filesystem::exists(dir)) << "work started for n=" << n;
  }
  // The same limit lets a small problem through.
  const Outcome small = RunShell(
      "CONTACTBENCH_MEMORY_LIMIT=1e9 " + std::string(CONTACTBENCH_BINARY) +
      " run --problem block --set n=4 --formulation implicit-fb --out " + dir.string() + " 2>&1");
  EXPECT_EQ(small.status, 0) << small.output;
  std::filesystem::remove_all(dir);
}

// Under an address-space limit (RLIMIT_AS, from `ulimit -v`) the problem is refused naming that
// limit; insisted on with --allow-memory, the std::bad_alloc is reported as what ran out of
// memory (here the build of the problem), with exit 3.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CONTACTBENCH_TEST_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define CONTACTBENCH_TEST_UNDER_ASAN 1
#endif

TEST(CliTest, RunningOutOfMemorySaysWhileDoingWhat) {
#ifdef CONTACTBENCH_TEST_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer maps terabytes of shadow memory: the binary cannot start "
                  "under the address-space limit this test sets";
#endif
  const auto dir = TempDir("memory_bad_alloc");
  // One OpenBLAS thread: the threaded OpenBLAS maps a buffer per worker at start-up and, when the
  // address-space limit refuses it, waits for it forever (docs/hardening.md "Memory").
  const std::string run =
      "ulimit -v 250000; OPENBLAS_NUM_THREADS=1 " + std::string(CONTACTBENCH_BINARY) +
      " run --problem block --set n=600 --formulation implicit-fb --out " + dir.string();
  const Outcome refused = RunShell("(" + run + ") 2>&1");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_TRUE(RefusedOption(refused.output, At("", {"RLIMIT_AS", "--allow-memory"})));
  EXPECT_EQ(refused.output.find("usage:"), std::string::npos) << refused.output;  // a data error
  const Outcome insisted = RunShell("(" + run + " --allow-memory) 2>&1");
  EXPECT_EQ(insisted.status, 3) << insisted.output;
  // The stage that ran out, in the words docs/cli.md lists for exit status 3 (its contract).
  EXPECT_TRUE(RefusedOption(insisted.output, At("", {"out of memory while building the problem"})));
  // Built before --out is claimed: nothing was written there.
  EXPECT_FALSE(std::filesystem::exists(dir / "steps.csv"));
  std::filesystem::remove_all(dir);
}

}  // namespace

namespace {

// ipopt-mpcc on a steeper two-bar truss pressed onto its floor: on the floor its steps crawl at
// arc lengths ~1e-5 (twice that ends "Solved_To_Acceptable_Level" with comp_res ~2e-4), which
// ran on to the last step and exited 0. The path now stops as stagnating: exit 3, the reason in
// the summary and in run.json.
TEST(CliTest, AStagnatingPathExitsWith3SayingSo) {
#ifndef CONTACTBENCH_HAVE_IPOPT
  GTEST_SKIP() << "built without Ipopt";
#endif
  const auto dir = TempDir("stagnation");
  const Outcome o = RunCli(
      "run --problem two-bar-obstacle --set height=1 --formulation ipopt-mpcc --arc-length 0.02 "
      "--steps 200 --out " +
      dir.string());
  EXPECT_EQ(o.status, 3) << o.output;
  const auto json = nlohmann::json::parse(std::ifstream(dir / "run.json"));
  EXPECT_EQ(json["exit_status"], 3);
  // The reason recorded is the stagnation (the path stopper's, src/path/stagnation.h), and the
  // summary says the same.
  const std::string reason = json["reason"].get<std::string>();
  EXPECT_NE(reason.find("stagnat"), std::string::npos) << json.dump();
  EXPECT_NE(o.output.find(reason), std::string::npos) << o.output;
  std::filesystem::remove_all(dir);
}

}  // namespace
