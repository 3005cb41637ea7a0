// `plate-3d`: the neo-Hookean plate traced by arc length onto the cylinder through `contactbench
// run`; every row of bottom nodes that comes into contact is a kink, located and verified.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "run_contactbench.h"

namespace cb {
namespace {

TEST(PlateTest, ArcLengthTraceLocatesTheContactChanges) {
  const auto out = std::filesystem::temp_directory_path() / "contactbench_plate_3d";
  std::filesystem::remove_all(out);
  const testing_support::CliOutcome run = testing_support::RunContactbench(
      "run --problem plate-3d --formulation implicit-fb --steps 40 --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.output;
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
