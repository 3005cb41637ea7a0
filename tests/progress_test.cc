// The progress line of `contactbench run`: its time estimates, and the line itself as a
// terminal sees it (the run's standard error on a pseudo-terminal).
#include "harness/progress.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "run_contactbench.h"
#include "source_tree.h"

namespace {

using cb::harness::ClockText;
using cb::harness::LineText;
using cb::harness::SlowWorkText;
using cb::harness::TimeText;

TEST(ProgressTest, ClockTextShowsMinutesAndSecondsThenHours) {
  EXPECT_EQ(ClockText(0.0), "0:00");
  EXPECT_EQ(ClockText(65.4), "1:05");
  EXPECT_EQ(ClockText(3600.0 * 2 + 3 * 60 + 9), "2:03:09");
}

TEST(ProgressTest, TheTimeLeftIsTheElapsedTimePerStepTimesTheStepsLeft) {
  // 10 s for 2 of 8 steps: 5 s a step, 6 steps left.
  EXPECT_EQ(TimeText(10.0, 2, 8), "elapsed 0:10, left ~0:30");
  // Nothing done yet, or everything: no estimate.
  EXPECT_EQ(TimeText(10.0, 0, 8), "elapsed 0:10");
  EXPECT_EQ(TimeText(10.0, 8, 8), "elapsed 0:10");
}

TEST(ProgressTest, TheLineCarriesANoticeOnlyWhenThereIsOne) {
  EXPECT_EQ(LineText("step 2/8", 10.0, 2, 8, ""), "\rstep 2/8  elapsed 0:10, left ~0:30\x1b[K");
  const std::string line = LineText("step 2/8", 10.0, 2, 8, "slow");
  EXPECT_EQ(line.rfind("\rstep 2/8  elapsed 0:10, left ~0:30", 0), 0u) << line;
  EXPECT_NE(line.find("slow"), std::string::npos) << line;
  EXPECT_EQ(line.rfind("\x1b[K"), line.size() - 3) << line;
}

TEST(ProgressTest, AFallBackNoticeNamesBothSolversAndTheSize) {
  const std::string text = SlowWorkText({"cholmod", "klu", 14739, 1200000});
  EXPECT_NE(text.find("cholmod"), std::string::npos) << text;
  EXPECT_NE(text.find("klu"), std::string::npos) << text;
  EXPECT_NE(text.find("14739 x 14739"), std::string::npos) << text;
  EXPECT_NE(text.find("minutes"), std::string::npos) << text;
}

// Off a terminal a reported fall-back shows nothing, as the rest of the line.
TEST(ProgressTest, OffATerminalAReportedFallbackShowsNothing) {
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  {
    cb::harness::ProgressLine line(file);
    line.ShowSlowWork();
    line.Update("step 1/2", 0, 2);
    cb::ReportSlowWork({"cholmod", "klu", 14739, 1200000});
  }
  cb::ReportSlowWork({"cholmod", "klu", 1, 1});  // the line is gone: nothing listens
  EXPECT_EQ(std::ftell(file), 0L);
  std::fclose(file);
}

// On a terminal it is shown after the last text, until the next Update.
TEST(ProgressTest, OnATerminalAReportedFallbackIsShownAfterTheLastText) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(grantpt(master), 0);
  ASSERT_EQ(unlockpt(master), 0);
  std::FILE* terminal = std::fopen(ptsname(master), "w");
  ASSERT_NE(terminal, nullptr);
  {
    cb::harness::ProgressLine line(terminal);
    line.ShowSlowWork();
    line.Update("step 1/2", 0, 2);
    cb::ReportSlowWork({"cholmod", "klu", 14739, 1200000});
  }
  std::fclose(terminal);
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(master, buffer, sizeof buffer)) > 0;) {
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.find('\n') != std::string::npos) break;  // End()'s newline: all is here
  }
  close(master);
  const std::string notice = SlowWorkText({"cholmod", "klu", 14739, 1200000});
  const std::size_t last = text.rfind("\rstep 1/2  elapsed ");
  ASSERT_NE(last, std::string::npos) << text;
  EXPECT_NE(text.find(notice, last), std::string::npos) << text;
}

struct Terminal {
  int status = -1;
  std::string text;  // what the terminal received
};

// Runs the suite driver with `args` and its standard error on a pseudo-terminal (standard
// output to /dev/null), and returns what the terminal received.
Terminal RunOnTerminal(const std::vector<std::string>& args) {
  Terminal out;
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0) return out;
  const std::string slave_name = ptsname(master);
  const pid_t pid = fork();
  if (pid == 0) {
    setsid();
    const int slave = open(slave_name.c_str(), O_RDWR);
    const int null = open("/dev/null", O_WRONLY);
    if (slave < 0 || null < 0) _exit(127);
    dup2(slave, STDERR_FILENO);
    dup2(null, STDOUT_FILENO);
    std::vector<char*> argv{const_cast<char*>(CONTACTBENCH_BINARY)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(CONTACTBENCH_BINARY, argv.data());
    _exit(127);
  }
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(master, buffer, sizeof buffer);
    if (n > 0) {
      out.text.append(buffer, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EIO: every holder of the terminal's other side has closed it
    }
  }
  close(master);
  int raw = 0;
  waitpid(pid, &raw, 0);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

std::string Example(const std::string& name) {
  return (::cb::testing_support::SourceRoot() / "examples" / name).string();
}

TEST(ProgressTest, OnATerminalEveryRewriteClearsTheLineAndTheSummaryStartsALine) {
  const auto dir = std::filesystem::temp_directory_path() / "contactbench_progress_terminal";
  std::filesystem::remove_all(dir);
  const Terminal t = RunOnTerminal({"run", "--problem-file", Example("truss-2d-bar-wall.json"),
                                    "--formulation", "implicit-fb", "--out", dir.string()});
  ASSERT_EQ(t.status, 0) << t.text;
  // Each rewrite is "\r" + text + erase-to-end-of-line, so no rest of a longer line stays.
  std::size_t rewrites = 0;
  for (std::size_t at = t.text.find('\r'); at != std::string::npos;
       at = t.text.find('\r', at + 1)) {
    const std::size_t end = t.text.find_first_of("\r\n", at + 1);
    if (end == at + 1) continue;  // the terminal's own "\r\n" for a newline
    ++rewrites;
    const std::string line = t.text.substr(at + 1, end - at - 1);
    EXPECT_EQ(line.rfind("\x1b[K"), line.size() - 3) << line;
    EXPECT_NE(line.find("elapsed "), std::string::npos) << line;
  }
  EXPECT_GE(rewrites, 40u) << t.text;  // one per step at least
  EXPECT_NE(t.text.find(", left ~"), std::string::npos) << t.text;
  // The summary is a line of its own: a newline ends the progress line before it.
  const std::size_t summary = t.text.find("truss-2d-bar-wall implicit-fb: ");
  ASSERT_NE(summary, std::string::npos) << t.text;
  ASSERT_GT(summary, 0u);
  EXPECT_EQ(t.text[summary - 1], '\n') << t.text;
  std::filesystem::remove_all(dir);
}

TEST(ProgressTest, OffATerminalNothingButTheSummaryIsShown) {
  const auto dir = std::filesystem::temp_directory_path() / "contactbench_progress_pipe";
  std::filesystem::remove_all(dir);
  const auto run = cb::testing_support::RunContactbench(
      "run --problem-file " + Example("truss-2d-bar-wall.json") +
      " --formulation implicit-fb --out " + dir.string());
  EXPECT_EQ(run.status, 0) << run.output;
  const std::string& text = run.output;
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_EQ(text.find('\x1b'), std::string::npos) << text;
  EXPECT_EQ(text.rfind("truss-2d-bar-wall implicit-fb: ", 0), 0u) << text;
  std::filesystem::remove_all(dir);
}

}  // namespace
