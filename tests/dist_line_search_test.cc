// The distributed Newton's line search (formulations/petsc_dist/dist_line_search.h) is the serial
// Newton's: on P1 at n = 10 from the cold start (where PETSc's monotone `bt` took 55 iterations
// against the serial 16) dist-implicit-fb takes the serial implicit-fb's iterations with the
// same line-search factors, cold (the nonmonotone window) and warm (monotone); a
// -snes_linesearch_type the user names is PETSc's own again.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fixture_start.h"
#include "fixtures.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "formulations/petsc_dist/petsc_dist.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

using fixtures::FindFixture;
using fixtures::Fixture;
using fixtures::StartFor;

// The line-search factors of the iterations from the first on (the distributed history also
// records iteration 0, the start).
std::vector<double> Factors(const StepResult& result) {
  std::vector<double> factors;
  for (const IterationRecord& record : result.history) {
    if (record.iteration >= 1) factors.push_back(record.step_length);
  }
  return factors;
}

TEST(DistLineSearchTest, TheDistributedNewtonSearchesAsTheSerialOne) {
  if (!DistAvailable()) GTEST_SKIP() << "built without PETSc";
  const Fixture& f = FindFixture("block_n10");
  const StepProblem step = f.Step();
  for (const StartKind kind : {StartKind::kCold, StartKind::kWarm}) {
    SCOPED_TRACE(ToString(kind));
    // The serial full route (Newton on all the unknowns), the method the distributed one runs.
    FormulationConfig full_route;
    full_route.options["reduced_newton"] = "0";
    const StepResult serial = MakeImplicitFb(full_route)->Solve(step, StartFor(f, kind));
    const StepResult dist = MakeDistImplicitFb({})->Solve(step, StartFor(f, kind));
    ASSERT_EQ(serial.status, Status::kConverged) << serial.message;
    ASSERT_EQ(dist.status, Status::kConverged) << dist.message;
    EXPECT_TRUE(Judge(step, dist.point, 1e-8).verified);
    EXPECT_EQ(dist.counts.iterations, serial.counts.iterations);
    const std::vector<double> a = Factors(serial), b = Factors(dist);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k)
      EXPECT_NEAR(a[k], b[k], 1e-8) << "iteration " << k + 1;
  }
}

TEST(DistLineSearchTest, ALineSearchTheUserNamesIsPetscsOwn) {
  if (!DistAvailable()) GTEST_SKIP() << "built without PETSc";
  const Fixture& f = FindFixture("block_n10");
  const StepProblem step = f.Step();
  FormulationConfig config;
  config.options["petsc_options"] = "-snes_linesearch_type basic";
  const StepResult full_steps =
      MakeDistImplicitFb(config)->Solve(step, StartFor(f, StartKind::kCold));
  // PETSc's `basic` takes every full step: no factor below 1, whatever it makes of the solve.
  for (const double factor : Factors(full_steps)) EXPECT_EQ(factor, 1.0);
}

}  // namespace
}  // namespace cb
