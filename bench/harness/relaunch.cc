#include "harness/relaunch.h"

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace cb::harness {

namespace {
// Set in the relaunched process, so that it never relaunches again.
constexpr const char* kRelaunched = "CONTACTBENCH_RELAUNCHED";
}  // namespace

void RelaunchWithLibrariesFirst(const std::string& preload, char** argv) {
  if (preload.empty() || std::getenv(kRelaunched) != nullptr) return;
  const char* before = std::getenv("LD_PRELOAD");
  std::string list = preload;
  if (before != nullptr && *before != '\0') {
    list += ':';
    list += before;
  }
  if (setenv("LD_PRELOAD", list.c_str(), 1) != 0 || setenv(kRelaunched, "1", 1) != 0) return;
  execv("/proc/self/exe", argv);
}

}  // namespace cb::harness
