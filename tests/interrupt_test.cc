// Runs that stop keep what they did: `contactbench run` interrupted by SIGINT or
// SIGTERM finishes the record line it is writing, says where it stopped and exits with status 4;
// a run killed with SIGKILL leaves only whole lines. The records are read back here with a
// plain RFC 4180 reader.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "refusal.h"

extern char** environ;

namespace {

using Record = std::vector<std::string>;

// The records of a CSV file and whether the file ends with a whole one (a line break outside
// quotes). Quoted fields may hold commas, quotes ("") and line breaks.
struct Csv {
  std::vector<Record> records;
  bool ends_whole = true;
};

Csv ReadCsv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  Csv csv;
  Record record;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.push_back(field);
      field.clear();
    } else if (c == '\n') {
      record.push_back(field);
      field.clear();
      csv.records.push_back(record);
      record.clear();
    } else {
      field += c;
    }
  }
  csv.ends_whole = !quoted && field.empty() && record.empty();
  return csv;
}

std::size_t CountLines(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("contactbench_interrupt_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Starts the CLI with stdout and stderr in `log`.
pid_t Start(const std::vector<std::string>& arguments, const std::filesystem::path& log) {
  std::vector<std::string> args = {CONTACTBENCH_BINARY};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// Waits until `file` has at least `lines` lines (true) or the process ended or 120 s passed.
bool WaitForLines(pid_t pid, const std::filesystem::path& file, std::size_t lines) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    if (std::filesystem::exists(file) && CountLines(file) >= lines) return true;
    int raw = 0;
    if (waitpid(pid, &raw, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// Waits for the process (killing it after 120 s); the raw wait status, -1 on a timeout.
int Wait(pid_t pid) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    int raw = 0;
    if (waitpid(pid, &raw, WNOHANG) == pid) return raw;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  int raw = 0;
  waitpid(pid, &raw, 0);
  return -1;
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Every record has the header's number of fields and the file ends with a whole record.
void ExpectWholeRecords(const std::filesystem::path& path, const Csv& csv) {
  ASSERT_FALSE(csv.records.empty()) << path;
  EXPECT_TRUE(csv.ends_whole) << path << " ends inside a record";
  const std::size_t width = csv.records.front().size();
  for (std::size_t k = 1; k < csv.records.size(); ++k) {
    EXPECT_EQ(csv.records[k].size(), width) << path << " record " << k;
  }
}

std::map<std::string, std::size_t> Columns(const Record& header) {
  std::map<std::string, std::size_t> columns;
  for (std::size_t i = 0; i < header.size(); ++i) columns[header[i]] = i;
  return columns;
}

const std::vector<std::string> kLongRun = {
    "run", "--problem", "arch-curved", "--formulation", "implicit-fb", "--steps", "100000"};

class InterruptTest : public testing::TestWithParam<int> {};

TEST_P(InterruptTest, StopsWithStatus4SayingWhereAndKeepsWholeRecords) {
  const int signal = GetParam();
  const auto dir = TempDir(signal == SIGINT ? "int" : "term");
  const auto log = dir / "log.txt";
  auto args = kLongRun;
  args.insert(args.end(), {"--out", dir.string()});
  const pid_t pid = Start(args, log);
  ASSERT_GT(pid, 0);
  // Some steps in: the run is well under way (the header and 30 records).
  ASSERT_TRUE(WaitForLines(pid, dir / "steps.csv", 31)) << ReadText(log);
  ASSERT_EQ(kill(pid, signal), 0);
  const int raw = Wait(pid);
  ASSERT_TRUE(WIFEXITED(raw)) << "not a normal exit: " << raw << "\n" << ReadText(log);
  EXPECT_EQ(WEXITSTATUS(raw), 4) << ReadText(log);

  const Csv steps = ReadCsv(dir / "steps.csv");
  ExpectWholeRecords(dir / "steps.csv", steps);
  ExpectWholeRecords(dir / "iterations.csv", ReadCsv(dir / "iterations.csv"));
  auto col = Columns(steps.records.front());
  for (const char* name : {"step", "accepted", "status", "verified"}) {
    ASSERT_TRUE(col.count(name)) << name;
  }
  // The accepted steps are 1, 2, ..., each verified; the last record is the step it stopped at:
  // accepted when it stopped after it, else the interrupted attempt, stopped by the caller.
  int accepted = 0;
  for (std::size_t k = 1; k < steps.records.size(); ++k) {
    const Record& r = steps.records[k];
    if (r[col["accepted"]] != "true") continue;
    ++accepted;
    EXPECT_EQ(std::stoi(r[col["step"]]), accepted);
    EXPECT_EQ(r[col["verified"]], "true");
  }
  EXPECT_GE(accepted, 30);
  const Record& last = steps.records.back();
  const int stopped_step = std::stoi(last[col["step"]]);
  if (last[col["accepted"]] == "false") {
    EXPECT_EQ(last[col["status"]], "stopped_by_caller");
    EXPECT_EQ(stopped_step, accepted + 1);
  } else {
    EXPECT_EQ(stopped_step, accepted);
  }

  // The run's line (the one naming its directory) says where it stopped and how many steps were
  // accepted: its first two numbers, as the records have them.
  const std::string output = ReadText(log);
  const std::size_t at = output.find(dir.string());
  ASSERT_NE(at, std::string::npos) << output;
  const std::size_t begin = output.rfind('\n', at);
  const std::string line = output.substr(begin == std::string::npos ? 0 : begin + 1,
                                         at - (begin == std::string::npos ? 0 : begin + 1));
  const std::vector<double> numbers = cb::testing_support::NumbersIn(line);
  ASSERT_GE(numbers.size(), 2u) << line;
  EXPECT_EQ(numbers[0], stopped_step) << line;
  EXPECT_EQ(numbers[1], accepted) << line;
  // The snapshot of the last accepted state is written too.
  const Csv solution = ReadCsv(dir / "solution.csv");
  ExpectWholeRecords(dir / "solution.csv", solution);
  ASSERT_GT(solution.records.size(), 1u);
  EXPECT_EQ(std::stoi(solution.records[1][0]), accepted);
  // run.json says how it ended, with the counts of the records.
  const auto run = nlohmann::json::parse(ReadText(dir / "run.json"));
  EXPECT_EQ(run.at("exit_status"), 4);
  EXPECT_TRUE(cb::testing_support::NamesNumber(run.at("reason").get<std::string>(), stopped_step));
  EXPECT_EQ(run.at("counts").at("accepted_steps"), accepted);
  EXPECT_EQ(run.at("counts").at("attempts"), static_cast<int>(steps.records.size()) - 1);
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Signals, InterruptTest, testing::Values(SIGINT, SIGTERM),
                         [](const testing::TestParamInfo<int>& info) {
                           return std::string(info.param == SIGINT ? "Sigint" : "Sigterm");
                         });

// compare stops the same way, during the reference path or a replay.
TEST(InterruptTest, CompareStopsWithStatus4AndWholeRecords) {
  const auto dir = TempDir("compare");
  const auto log = dir / "log.txt";
  const pid_t pid = Start({"compare", "--problem", "arch-curved", "--formulations",
                           "implicit-fb,nonsmooth-fb", "--steps", "100000", "--out", dir.string()},
                          log);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(WaitForLines(pid, dir / "kinks.csv", 3)) << ReadText(log);
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  const int raw = Wait(pid);
  ASSERT_TRUE(WIFEXITED(raw)) << raw << "\n" << ReadText(log);
  EXPECT_EQ(WEXITSTATUS(raw), 4) << ReadText(log);
  // run.json records the same ending.
  const auto run = nlohmann::json::parse(ReadText(dir / "run.json"));
  EXPECT_EQ(run.at("exit_status"), 4) << run.dump();
  for (const char* file : {"steps.csv", "iterations.csv", "kinks.csv", "runs.csv"}) {
    ExpectWholeRecords(dir / file, ReadCsv(dir / file));
  }
  std::filesystem::remove_all(dir);
}

// Waits until `file` exists (true) or the process ended or 120 s passed.
bool WaitForFile(pid_t pid, const std::filesystem::path& file) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    if (std::filesystem::exists(file)) return true;
    int raw = 0;
    if (waitpid(pid, &raw, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// --start near first solves the problem with the reference formulation, before any record is
// written: an interrupt there is an interruption (4), not a failed reference solve (3).
TEST(InterruptTest, AnInterruptDuringTheNearStartsReferenceSolveExits4) {
  const auto dir = TempDir("near");
  std::filesystem::create_directories(dir);
  const auto out = dir / "out";
  const pid_t pid = Start({"run", "--problem", "block", "--set", "n=200", "--formulation",
                           "implicit-fb", "--start", "near", "--out", out.string()},
                          dir / "log.txt");
  ASSERT_GT(pid, 0);
  // The lock is taken once the problem is built; the reference solve (seconds at n = 200)
  // starts right after it.
  ASSERT_TRUE(WaitForFile(pid, out / ".contactbench.lock")) << ReadText(dir / "log.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  const int raw = Wait(pid);
  const std::string said = ReadText(dir / "log.txt");
  ASSERT_TRUE(WIFEXITED(raw)) << raw << "\n" << said;
  EXPECT_EQ(WEXITSTATUS(raw), 4) << said;
  // The refusal names the option whose solve was interrupted.
  EXPECT_TRUE(cb::testing_support::Names(cb::testing_support::RefusalLine(said), {"--start near"}))
      << said;
  const auto run = nlohmann::json::parse(ReadText(out / "run.json"));
  EXPECT_EQ(run["exit_status"], 4) << run.dump();
  EXPECT_FALSE(std::filesystem::exists(out / "steps.csv"));
  std::filesystem::remove_all(dir);
}

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
// Under AddressSanitizer the run's ending (its records, the leak check at exit with the abandoned
// worker still factorising) is several times slower: 15.5 s once in CI's sanitizer job on a
// loaded machine. The factorisation it abandons takes minutes even in Release, so 45 s there
// still tells an abandoned factorisation from a finished one.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)  // clang's word for it; gcc defines __SANITIZE_ADDRESS__
#define CB_INTERRUPT_UNDER_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(CB_INTERRUPT_UNDER_ADDRESS_SANITIZER)
constexpr double kSecondsToAct = 45.0;
#else
constexpr double kSecondsToAct = 15.0;
#endif

const std::vector<std::string> kHertzFallingBackToKlu = {
    "run", "--problem", "hertz-3d", "--set", "youngs_modulus=1e20", "--formulation", "implicit-fb"};

// Runs `run` (hertz-3d with E = 1e20 unless given) until a factorisation's worker thread named
// `worker` runs (core/abandonable_work.h), waits `settle` more, sends SIGTERM, and checks that
// the run ends as an interrupted one in seconds, its run.json written and the abandoned solve
// recorded as stopped, not as a failed step (when `in_a_step`: the tangent predictor's
// factorisation comes before the first step).
void ExpectASigtermDuringTheWorkerActsInSeconds(
    const std::string& label, const std::string& worker, std::chrono::milliseconds settle,
    std::vector<std::string> run = kHertzFallingBackToKlu, bool in_a_step = true) {
  const auto dir = TempDir(label);
  std::filesystem::create_directories(dir);
  const auto out = dir / "out";
  run.insert(run.end(), {"--out", out.string()});
  const pid_t pid = Start(run, dir / "log.txt");
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(WaitForFile(pid, out / ".contactbench.lock")) << ReadText(dir / "log.txt");
  const auto worker_running = [pid, &worker] {
    const auto tasks = std::filesystem::path("/proc") / std::to_string(pid) / "task";
    std::error_code ec;
    for (const auto& task : std::filesystem::directory_iterator(tasks, ec)) {
      if (ReadText(task.path() / "comm").rfind(worker, 0) == 0) return true;
    }
    return false;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(240);
  int early = 0;
  while (!worker_running() && std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &early, WNOHANG) == pid) {
      FAIL() << "the run ended (status " << early << ") with no " << worker << " worker\n"
             << ReadText(dir / "log.txt");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(worker_running()) << "no " << worker << " worker thread\n"
                                << ReadText(dir / "log.txt");
  std::this_thread::sleep_for(settle);
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  const auto sent = std::chrono::steady_clock::now();
  const int raw = Wait(pid);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string said = ReadText(dir / "log.txt");
  ASSERT_TRUE(WIFEXITED(raw)) << raw << "\n" << said;
  EXPECT_EQ(WEXITSTATUS(raw), 4) << said;
  EXPECT_LT(seconds, kSecondsToAct) << said;
  const auto run_json = nlohmann::json::parse(ReadText(out / "run.json"));
  EXPECT_EQ(run_json["exit_status"], 4) << run_json.dump();
  if (in_a_step) {
    // The abandoned solve is the last record, stopped, not failed.
    const Csv steps = ReadCsv(out / "steps.csv");
    ASSERT_GE(steps.records.size(), 2u);  // the header and a row
    auto col = Columns(steps.records.front());
    ASSERT_TRUE(col.count("status"));
    EXPECT_EQ(steps.records.back()[col["status"]], "stopped_by_caller");
  }
  std::filesystem::remove_all(dir);
}

// hertz-3d with E = 1e20 falls back from the condensed Cholesky to KLU, whose factorisation of
// the 3-D system takes minutes: a SIGTERM during it acts in seconds (solvers/interruptible_klu.h;
// before, it took 73 s). The worker appears after the condensed Cholesky's attempt (tens of
// seconds on a loaded machine); the signal comes a second after it.
TEST(InterruptTest, ASigtermDuringALongFactorisationActsInSeconds) {
  ExpectASigtermDuringTheWorkerActsInSeconds("factorisation", "klu-factor",
                                             std::chrono::milliseconds(1000));
}

// Before each KLU factorisation of that run after the first, CHOLMOD factorises the condensed
// system whole (CondensedSystem::FactorizeWhole): 2 s on a quiet machine, 18-36 s under load,
// and a SIGTERM waited for it. It runs on a worker too (solvers/interruptible_cholmod.h): a
// SIGTERM as soon as it starts acts in seconds, before the factorisation ends.
TEST(InterruptTest, ASigtermDuringACholmodFactorisationActsInSeconds) {
  ExpectASigtermDuringTheWorkerActsInSeconds("cholmod", "cholmod-factor",
                                             std::chrono::milliseconds(0));
}

// P1's first Newton iteration factorises the 181 202-dof stiffness for the contact-block update
// (ContactBlockFactor::Factorize: 5-40 s on this machine under load), and a SIGTERM waited for
// it. It runs on a worker too: a SIGTERM as soon as it starts acts in seconds.
TEST(InterruptTest, ASigtermDuringTheContactBlockFactorisationActsInSeconds) {
  ExpectASigtermDuringTheWorkerActsInSeconds("contact_block", "cholmod-factor",
                                             std::chrono::milliseconds(0),
                                             {"run", "--problem", "block", "--set", "n=300",
                                              "--formulation", "implicit-fb", "--start", "cold"});
}

// The arc-length start's tangent predictor factorises the bordered stiffness (Eigen's LDL^T and
// LU: over 90 s on plate-3d at 32 x 32 x 32), and a SIGTERM waited for it. It runs on a worker
// (path/stability.h): a SIGTERM as soon as it starts acts in seconds, before any step.
TEST(InterruptTest, ASigtermDuringTheTangentPredictorActsInSeconds) {
  ExpectASigtermDuringTheWorkerActsInSeconds(
      "tangent", "stiffness-fact", std::chrono::milliseconds(0),
      {"run", "--problem", "plate-3d", "--set", "nx=16", "--set", "ny=16", "--set", "nz=16",
       "--formulation", "implicit-fb"},
      false);
}
#endif

// A second run into the directory of a running one is refused before it writes anything, and
// names the first one's pid; the first one's records stay its own.
TEST(InterruptTest, ASecondRunIntoTheSameDirectoryIsRefused) {
  const auto dir = TempDir("second");
  auto args = kLongRun;
  args.insert(args.end(), {"--out", (dir / "out").string()});
  const pid_t first = Start(args, dir / "first.txt");
  ASSERT_GT(first, 0);
  ASSERT_TRUE(WaitForLines(first, dir / "out" / "steps.csv", 11)) << ReadText(dir / "first.txt");
  const pid_t second = Start({"compare", "--problem", "two-bar", "--formulations", "implicit-fb",
                              "--overwrite", "--out", (dir / "out").string()},
                             dir / "second.txt");
  ASSERT_GT(second, 0);
  const int raw = Wait(second);
  const std::string said = ReadText(dir / "second.txt");
  ASSERT_TRUE(WIFEXITED(raw)) << raw << "\n" << said;
  EXPECT_EQ(WEXITSTATUS(raw), 2) << said;
  // Refused at --out, naming the run that holds it by its pid.
  EXPECT_TRUE(cb::testing_support::RefusedOption(said, cb::testing_support::At("--out")));
  EXPECT_TRUE(cb::testing_support::NamesNumber(cb::testing_support::RefusalLine(said), first));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "runs.csv"));
  ASSERT_EQ(kill(first, SIGTERM), 0);
  const int first_raw = Wait(first);
  ASSERT_TRUE(WIFEXITED(first_raw)) << ReadText(dir / "first.txt");
  EXPECT_EQ(WEXITSTATUS(first_raw), 4) << ReadText(dir / "first.txt");
  // Each steps.csv row is the first run's: its problem, steps 1, 2, ... in order.
  const Csv steps = ReadCsv(dir / "out" / "steps.csv");
  ExpectWholeRecords(dir / "out" / "steps.csv", steps);
  auto col = Columns(steps.records.front());
  for (std::size_t k = 1; k < steps.records.size(); ++k) {
    EXPECT_EQ(steps.records[k][col["problem"]], "arch-curved") << k;
  }
  std::filesystem::remove_all(dir);
}

// SIGKILL cannot be handled: whatever was written is whole records (each is written by one
// write and flushed).
TEST(InterruptTest, KilledRunLeavesOnlyWholeRecords) {
  const auto dir = TempDir("kill");
  auto args = kLongRun;
  args.insert(args.end(), {"--out", dir.string()});
  const pid_t pid = Start(args, dir / "log.txt");
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(WaitForLines(pid, dir / "steps.csv", 21)) << ReadText(dir / "log.txt");
  // Kill while it writes: a few random moments after rows have started to flow.
  std::this_thread::sleep_for(std::chrono::milliseconds(7));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  const int raw = Wait(pid);
  ASSERT_TRUE(WIFSIGNALED(raw));
  EXPECT_EQ(WTERMSIG(raw), SIGKILL);
  for (const char* file : {"steps.csv", "iterations.csv", "kinks.csv"}) {
    const Csv csv = ReadCsv(dir / file);
    ExpectWholeRecords(dir / file, csv);
  }
  const Csv steps = ReadCsv(dir / "steps.csv");
  EXPECT_GE(steps.records.size(), 21u);
  std::filesystem::remove_all(dir);
}

}  // namespace
