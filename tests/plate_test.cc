// `plate-3d`: the neo-Hookean plate traced by arc length onto the cylinder through `contactbench
// run`; every row of bottom nodes that comes into contact is a kink, located and verified.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace cb {
namespace {

TEST(PlateTest, ArcLengthTraceLocatesTheContactChanges) {
  const auto out = std::filesystem::temp_directory_path() / "contactbench_plate_3d";
  std::filesystem::remove_all(out);
  const std::string command =
      std::string(CONTACTBENCH_BINARY) +
      " run --problem plate-3d --formulation implicit-fb --steps 40 --out " + out.string() +
      " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  std::string output;
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  const int raw = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(raw));
  ASSERT_EQ(WEXITSTATUS(raw), 0) << output;
  // docs/problems.md: by step 40 the mid-span row (3 nodes) and the rows at +-0.5 m (6) are in
  // contact; each is a located kink, verified and between its steps.
  std::ifstream kinks(out / "kinks.csv");
  std::string line;
  std::getline(kinks, line);
  int rows = 0;
  while (std::getline(kinks, line)) {
    EXPECT_NE(line.find(",true,true,"), std::string::npos) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 9);
}

}  // namespace
}  // namespace cb
