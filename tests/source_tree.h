// The repository's root, for tests that read its files (examples/, tests/data/, fuzz/). Set by
// CMake as an absolute path, so the test binary finds them from any working directory
// (__FILE__ is relative to the build directory under Ninja).
#pragma once

#include <filesystem>

namespace cb::testing_support {

inline std::filesystem::path SourceRoot() { return std::filesystem::path(CONTACTBENCH_SOURCE_DIR); }

}  // namespace cb::testing_support
