// `contactbench run` of one of the examples/ problem files, for tests that read its records.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "source_tree.h"

namespace cb::test_support {

inline const std::filesystem::path kExamples = ::cb::testing_support::SourceRoot() / "examples";

// Runs examples/`example` with implicit-fb (and the options `more`) into the fresh directory
// TMP/contactbench_`name` and returns it; a failed run fails the calling test.
inline std::filesystem::path RunExample(const std::string& example, const std::string& name,
                                        const std::string& more = "") {
  const auto dir = std::filesystem::temp_directory_path() / ("contactbench_" + name);
  std::filesystem::remove_all(dir);
  const std::string command = std::string(CONTACTBENCH_BINARY) + " run --problem-file " +
                              (kExamples / example).string() + " --formulation implicit-fb " +
                              more + " --out " + dir.string() + " 2>/dev/null";
  const int raw = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << command;
  return dir;
}

}  // namespace cb::test_support
