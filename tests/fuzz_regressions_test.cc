// The inputs the reader fuzzers (fuzz/, scripts/run_fuzz.sh) found crashes with, kept in
// fuzz/regressions/, and the seed corpus: each is handed to both readers exactly as the fuzzers
// do, in the ordinary test binary (no libFuzzer). Refusal with std::invalid_argument is the
// contract; any other exception fails the test, and under scripts/check_sanitizers.sh so does
// any memory or undefined-behaviour error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../fuzz/readers.h"
#include "source_tree.h"

namespace cb {
namespace {

const std::filesystem::path kRoot = ::cb::testing_support::SourceRoot();

std::vector<std::filesystem::path> FilesUnder(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::exists(dir)) return files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
  }
  return files;
}

void FeedBothReaders(const std::filesystem::path& file) {
  SCOPED_TRACE(file.string());
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const auto* data = reinterpret_cast<const std::uint8_t*>(text.data());
  EXPECT_NO_THROW(fuzz::ProblemFileInput(data, text.size(), (kRoot / "examples").string()));
  EXPECT_NO_THROW(fuzz::GmshInput(data, text.size()));
}

// A missing or emptied fuzz/regressions/ fails here rather than passing having read nothing.
TEST(FuzzRegressionsTest, KeptCrashInputsAreRefusedOrRead) {
  const std::filesystem::path dir = kRoot / "fuzz" / "regressions";
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir << " is missing";
  const auto files = FilesUnder(dir);
  ASSERT_FALSE(files.empty()) << dir << " holds no kept input";
  for (const auto& file : files) FeedBothReaders(file);
  RecordProperty("inputs", static_cast<int>(files.size()));
}

// gmsh_fuzzer: a $Nodes header announcing 1e8 nodes sized a 2.4 GB matrix before any node was
// read. The count is now refused when the file cannot hold that many nodes.
TEST(FuzzRegressionsTest, NodeCountBeyondTheFileIsRefused) {
  const std::string text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 100000000 1 1\n";
  try {
    io::ParseGmsh(text, "big.msh");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("more than the file can hold"), std::string::npos)
        << e.what();
  }
}

TEST(FuzzRegressionsTest, SeedCorpusAndExamplesAreRefusedOrRead) {
  auto files = FilesUnder(kRoot / "fuzz" / "corpus");
  const auto examples = FilesUnder(kRoot / "examples");
  files.insert(files.end(), examples.begin(), examples.end());
  ASSERT_FALSE(files.empty());
  for (const auto& file : files) FeedBothReaders(file);
}

}  // namespace
}  // namespace cb
