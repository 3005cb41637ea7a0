// A distributed run repeated gives the same answer to the last bit: the same binary, problem and
// options, three times, write byte-identical solutions (docs/findings.md, "MUMPS's ordering and
// reproducibility": with MUMPS's METIS ordering P1 n = 100 gave three different last digits).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "run_contactbench.h"

namespace cb {
namespace {
#ifdef CONTACTBENCH_HAVE_PETSC

std::string SolutionOfARun(const std::string& linear, int run) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("contactbench_dist_reproducible_" + linear + "_" + std::to_string(getpid()) +
                    "_" + std::to_string(run));
  std::filesystem::remove_all(dir);
  const auto out = testing_support::RunContactbench(
      "run --problem block --set n=100 --formulation dist-active-set --option linear=" + linear +
      " --out " + dir.string());
  EXPECT_EQ(out.status, 0) << out.output;
  std::ifstream in(dir / "solution.csv", std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove_all(dir);
  return text.str();
}

TEST(DistReproducibleTest, ARepeatedRunWritesTheSameSolution) {
  for (const std::string linear : {"direct", "amg"}) {
    const std::string first = SolutionOfARun(linear, 0);
    ASSERT_FALSE(first.empty()) << linear;
    for (int run = 1; run < 3; ++run) {
      EXPECT_EQ(SolutionOfARun(linear, run), first) << linear << ": run " << run;
    }
  }
}

#endif  // CONTACTBENCH_HAVE_PETSC
}  // namespace
}  // namespace cb
