// Runs the contactbench binary of this build with arguments, for end-to-end tests.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace cb::testing_support {

struct CliOutcome {
  int status = -1;     // the exit status, -1 if it did not exit normally
  std::string output;  // stdout and stderr
};

inline CliOutcome RunContactbench(const std::string& arguments) {
  CliOutcome out;
  const std::string command = std::string(CONTACTBENCH_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out.output += buffer;
  const int raw = pclose(pipe);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

}  // namespace cb::testing_support
