// The bounds checked before a problem file is parsed (io/input_bounds.h): its size and its
// nesting, refused at once with the file named, and the size bound lifted when asked.
#include "io/input_bounds.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/problem_file.h"
#include "source_tree.h"

namespace {

namespace fs = std::filesystem;

std::string RefusalOf(const std::string& text) {
  try {
    cb::io::ParseProblemFile(text, "deep.json", ".");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(InputBoundsTest, NestingDeeperThanTheBoundIsRefusedWithItsPosition) {
  const int depth = cb::io::kJsonMaxDepth + 1;
  const std::string deep = std::string(depth, '[') + std::string(depth, ']');
  const std::string refusal = RefusalOf(deep);
  EXPECT_NE(refusal.find("deep.json: line 1, column " + std::to_string(depth)), std::string::npos)
      << refusal;
  EXPECT_NE(refusal.find("nested more than 32 deep"), std::string::npos) << refusal;
  // A million levels: refused by the scan, before the parser sees them.
  const std::string hostile(1000000, '[');
  EXPECT_NE(RefusalOf(hostile).find("nested more than"), std::string::npos);
  // Brackets inside strings (escaped quotes among them) are text, not nesting.
  const std::string quoted =
      "{\"name\": \"" + std::string(100, '[') + "\\\"" + std::string(100, '{') + "\"}";
  EXPECT_EQ(RefusalOf(quoted).find("nested more than"), std::string::npos) << RefusalOf(quoted);
}

TEST(InputBoundsTest, AFileLargerThanTheBoundIsRefusedBeforeItIsReadUnlessLifted) {
  const fs::path example =
      cb::testing_support::SourceRoot() / "examples" / "truss-2d-bar-wall.json";
  const auto size = fs::file_size(example);
  try {
    cb::io::LoadProblemFile(example.string(), {}, size - 1);
    FAIL() << "a file above the bound was read";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(example.string()), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(size) + " bytes"), std::string::npos) << what;
    EXPECT_NE(what.find("--allow-memory"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(cb::io::LoadProblemFile(example.string(), {}, size));
  EXPECT_NO_THROW(cb::io::LoadProblemFile(example.string(), {}, 0));  // no bound
}

}  // namespace
