// Runs the contactbench binary of this build (or any shell command) and captures its output,
// exit status and wall time, for end-to-end tests. The one popen loop of the tests.
#pragma once

#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace cb::testing_support {

struct CliOutcome {
  int status = -1;       // the exit status, -1 if it did not exit normally
  std::string output;    // what the command wrote to the pipe (stdout, and stderr if redirected)
  double seconds = 0.0;  // wall time from start to exit
};

// `command` run by the shell, its stdout captured (redirect stderr in `command` to keep it).
inline CliOutcome RunShell(const std::string& command) {
  CliOutcome out;
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out.output += buffer;
  const int raw = pclose(pipe);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

// `contactbench ARGUMENTS` with `streams` ("2>&1", "2>/dev/null", "2>&1 >/dev/null"), after
// `prefix` ("timeout -s KILL 60 env VAR=VALUE"; "" for none).
inline CliOutcome RunContactbench(const std::string& arguments, const std::string& streams = "2>&1",
                                  const std::string& prefix = "") {
  return RunShell((prefix.empty() ? "" : prefix + " ") + std::string(CONTACTBENCH_BINARY) + " " +
                  arguments + " " + streams);
}

}  // namespace cb::testing_support
