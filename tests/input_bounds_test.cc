// The bounds checked before a problem file is parsed (io/input_bounds.h): its size and its
// nesting, refused at once with the file named, and the size bound lifted when asked.
#include "io/input_bounds.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/problem_file.h"
#include "refusal.h"
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
  // At the bracket one past the bound, giving the bound.
  const cb::testing_support::Refusal at_bound =
      cb::testing_support::At("line 1, column " + std::to_string(depth));
  EXPECT_TRUE(cb::testing_support::RefusedAt(refusal, "deep.json", at_bound));
  EXPECT_TRUE(cb::testing_support::NamesNumber(refusal, cb::io::kJsonMaxDepth));
  // A million levels: refused by the scan at the same bracket, before the parser sees them.
  const std::string hostile(1000000, '[');
  EXPECT_TRUE(cb::testing_support::RefusedAt(RefusalOf(hostile), "deep.json", at_bound));
  // Brackets inside strings (escaped quotes among them) are text, not nesting: the file is
  // parsed, and refused at its root for the field it lacks.
  const std::string quoted =
      "{\"name\": \"" + std::string(100, '[') + "\\\"" + std::string(100, '{') + "\"}";
  EXPECT_TRUE(cb::testing_support::RefusedAt(RefusalOf(quoted), "deep.json",
                                             cb::testing_support::At("/", {"kind"})));
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
    // The file, the option that lifts the bound, its size and the bound.
    EXPECT_TRUE(cb::testing_support::RefusedAt(what, example.string(),
                                               cb::testing_support::At("", {"--allow-memory"})));
    EXPECT_TRUE(cb::testing_support::NamesNumber(what, static_cast<double>(size)));
    EXPECT_TRUE(cb::testing_support::NamesNumber(what, static_cast<double>(size - 1)));
  }
  EXPECT_NO_THROW(cb::io::LoadProblemFile(example.string(), {}, size));
  EXPECT_NO_THROW(cb::io::LoadProblemFile(example.string(), {}, 0));  // no bound
}

}  // namespace
