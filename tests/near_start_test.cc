// The start near a known solution (path/near_start.h): the perturbation's closed form, and a
// start that lies within the offset of the reference formulation's verified solution.
#include "path/near_start.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "formulations/registry.h"
#include "problems/problem.h"

namespace cb {
namespace {

TEST(NearStartTest, PerturbsEachEntryByTheRelativeOffsetWithTheFixedPattern) {
  State s;
  s.u = Vec::LinSpaced(5, 1.0, 5.0);
  s.r = -Vec::LinSpaced(3, 2.0, 4.0);
  s.lambda = 0.75;
  const double delta = 0.1;
  const State near = PerturbedSolution(s, delta);
  ASSERT_EQ(near.u.size(), 5);
  ASSERT_EQ(near.r.size(), 3);
  for (int i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(near.u[i], s.u[i] * (1.0 + delta * std::sin(i + 1.0))) << i;
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(near.r[i], s.r[i] * (1.0 + delta * std::sin(i + 2.0))) << i;
  }
  EXPECT_EQ(near.lambda, s.lambda);
  // No offset, no change.
  EXPECT_EQ(PerturbedSolution(s, 0.0).u, s.u);
  EXPECT_EQ(PerturbedSolution(s, 0.0).r, s.r);
}

TEST(NearStartTest, StartsWithinTheOffsetOfTheReferenceSolution) {
  const Problem p = MakeProblem("block", {{"n", "4"}});
  auto reference = MakeFormulation("implicit-fb", FormulationConfig());
  const State zero = ZeroState(*p.model);
  PathOptions options;
  const PathSummary solved =
      SolveFixedLoad(*p.model, p.scales, zero, p.load, *reference, options, nullptr);
  ASSERT_EQ(solved.status, Status::kConverged) << solved.message;
  const double delta = 1e-2;
  State start;
  std::string why;
  auto fresh = MakeFormulation("implicit-fb", FormulationConfig());  // as the solve above
  ASSERT_TRUE(
      NearSolutionStart(*p.model, p.scales, zero, p.load, *fresh, options, delta, &start, &why))
      << why;
  const State& x = solved.final_state;
  ASSERT_EQ(start.u.size(), x.u.size());
  ASSERT_EQ(start.r.size(), x.r.size());
  double moved = 0.0;
  for (int i = 0; i < x.u.size(); ++i) {
    EXPECT_LE(std::abs(start.u[i] - x.u[i]), delta * std::abs(x.u[i]) * (1 + 1e-12)) << i;
    moved = std::max(moved, std::abs(start.u[i] - x.u[i]));
  }
  for (int i = 0; i < x.r.size(); ++i) {
    EXPECT_LE(std::abs(start.r[i] - x.r[i]), delta * std::abs(x.r[i]) * (1 + 1e-12)) << i;
  }
  EXPECT_GT(moved, 0.0);  // a start near the solution, not on it
}

TEST(NearStartTest, SaysWhyWhenTheReferenceSolveFails) {
  const Problem p = MakeProblem("block", {{"n", "4"}});
  auto reference = MakeFormulation("implicit-fb", FormulationConfig());
  PathOptions options;
  options.tolerance = 1e-300;  // no double meets it: the verdict refuses every answer
  options.max_cutbacks = 0;
  State start;
  std::string why;
  EXPECT_FALSE(NearSolutionStart(*p.model, p.scales, ZeroState(*p.model), p.load, *reference,
                                 options, 1e-2, &start, &why));
  EXPECT_FALSE(why.empty());
}

}  // namespace
}  // namespace cb
