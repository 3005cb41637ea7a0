// The distributed formulations' iterative linear solve (`linear=amg`: FGMRES with the augmented
// Schur-complement field split, GAMG on the du block; dist_formulation.cc, field_split.h) in one
// process, on P1 at n = 10 from the cold start: the answer must pass the verdict at 1e-8, carry the
// load on the wall and the floor (the fixture's check) and equal the direct solve's (MUMPS); two
// processes are checked by tests/mpi/two_processes.sh.
#include <gtest/gtest.h>

#include <stdexcept>

#include "fixture_start.h"
#include "fixtures.h"
#include "formulations/petsc_dist/petsc_dist.h"
#include "problems/problem.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

using fixtures::FindFixture;
using fixtures::Fixture;
using fixtures::StartFor;

FormulationConfig WithLinear(const std::string& linear) {
  FormulationConfig config;
  config.options["linear"] = linear;
  return config;
}

TEST(DistLinearSolveTest, AmgGivesTheDirectSolvesAnswerOnP1) {
  if (!DistAvailable()) GTEST_SKIP() << "built without PETSc";
  const Fixture& f = FindFixture("block_n10");
  const StepProblem step = f.Step();
  const StepResult amg =
      MakeDistActiveSet(WithLinear("amg"))->Solve(step, StartFor(f, StartKind::kCold));
  const StepResult direct =
      MakeDistActiveSet(WithLinear("direct"))->Solve(step, StartFor(f, StartKind::kCold));
  ASSERT_EQ(amg.status, Status::kConverged) << amg.message;
  EXPECT_TRUE(Judge(step, amg.point, 1e-8).verified);
  EXPECT_TRUE(f.CheckSolution(
      State{f.base.u + amg.point.du, amg.point.r, f.base.lambda + amg.point.dlambda}));
  EXPECT_TRUE(fixtures::RelativelyClose(amg.point.du, direct.point.du, 1e-6,
                                        f.problem.scales.length, "du"));
  // Krylov iterations, not one factorisation per Newton iteration; the tolerance of the preset
  // keeps Newton's count within one of the direct solve's.
  EXPECT_GT(amg.counts.linear_solves, 2 * amg.counts.iterations);
  EXPECT_LE(amg.counts.iterations, direct.counts.iterations + 1);
}

// The plain split (PCFIELDSPLIT on J itself, its selfp Schur complement missing the contact
// compliance) against the preset's augmented one (field_split.h): the same answer, and the
// augmented split needs fewer Krylov iterations (measured on this fixture: 84 against 116).
TEST(DistLinearSolveTest, TheAugmentedSplitNeedsFewerKrylovIterationsThanThePlainOne) {
  if (!DistAvailable()) GTEST_SKIP() << "built without PETSc";
  const Fixture& f = FindFixture("block_n10");
  const StepProblem step = f.Step();
  FormulationConfig plain = WithLinear("amg");
  plain.options["petsc_options"] =
      "-pc_type fieldsplit -pc_fieldsplit_type schur -pc_fieldsplit_schur_fact_type upper"
      " -pc_fieldsplit_schur_precondition selfp -fieldsplit_0_ksp_type preonly"
      " -fieldsplit_0_pc_type gamg -fieldsplit_0_mg_coarse_sub_pc_type svd"
      " -fieldsplit_0_mg_coarse_sub_pc_svd_zero_sing 1e-8 -fieldsplit_1_ksp_type preonly"
      " -fieldsplit_1_pc_type lu -fieldsplit_1_pc_factor_mat_solver_type mumps";
  const StepResult split = MakeDistActiveSet(plain)->Solve(step, StartFor(f, StartKind::kCold));
  const StepResult augmented =
      MakeDistActiveSet(WithLinear("amg"))->Solve(step, StartFor(f, StartKind::kCold));
  ASSERT_EQ(split.status, Status::kConverged) << split.message;
  ASSERT_EQ(augmented.status, Status::kConverged) << augmented.message;
  EXPECT_TRUE(fixtures::RelativelyClose(augmented.point.du, split.point.du, 1e-6,
                                        f.problem.scales.length, "du"));
  EXPECT_EQ(augmented.counts.iterations, split.counts.iterations);
  EXPECT_LT(augmented.counts.linear_solves, split.counts.linear_solves);
}

// hertz-3d (supports on its symmetry planes: nodes of 1, 2 and 3 free components) with amg: the
// node-blocked split (node_blocks.h) gives GAMG whole nodes and the rigid modes; before it, the
// solve failed with DIVERGED_LINEAR_SOLVE (docs/scale-out.md "Multigrid with supports"). The
// answer must pass the verdict, carry the quarter load (the sphere's -7.5) and equal the direct
// solve's, within one Newton iteration of its count.
TEST(DistLinearSolveTest, AmgSolvesTheSupportedHertzBody) {
  if (!DistAvailable()) GTEST_SKIP() << "built without PETSc";
  const Problem p = MakeProblem("hertz-3d", {{"n", "4"}, {"nz", "4"}});
  const StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(1.0),
                         p.scales};
  StartPoint start;
  start.kind = StartKind::kWarm;
  start.du = Vec::Zero(p.model->num_dofs());
  start.dlambda = 1.0;
  start.r = Vec::Zero(p.model->num_pairs());
  const StepResult amg = MakeDistActiveSet(WithLinear("amg"))->Solve(step, start);
  const StepResult direct = MakeDistActiveSet(WithLinear("direct"))->Solve(step, start);
  ASSERT_EQ(amg.status, Status::kConverged) << amg.message;
  ASSERT_EQ(direct.status, Status::kConverged) << direct.message;
  EXPECT_TRUE(Judge(step, amg.point, 1e-8).verified);
  EXPECT_NEAR(amg.point.r.sum(), -7.5, 1e-6);
  EXPECT_TRUE(
      fixtures::RelativelyClose(amg.point.du, direct.point.du, 1e-6, p.scales.length, "du"));
  // The Krylov tolerance keeps Newton's count within one of the direct solve's (as on P1).
  EXPECT_LE(amg.counts.iterations, direct.counts.iterations + 1);
}

// A Krylov solve that stops short is reported as such, with its count and residual, not as a
// bare SNES reason or a singular matrix: two FGMRES iterations cannot reach 1e-8 on P1.
TEST(DistLinearSolveTest, AnUnconvergedKrylovSolveSaysSo) {
  if (!DistAvailable()) GTEST_SKIP() << "built without PETSc";
  const Fixture& f = FindFixture("block_n10");
  FormulationConfig config = WithLinear("amg");
  config.options["petsc_options"] = "-ksp_max_it 2";
  const StepResult result =
      MakeDistActiveSet(config)->Solve(f.Step(), StartFor(f, StartKind::kCold));
  EXPECT_EQ(result.status, Status::kFailed);
  EXPECT_NE(result.message.find("the linear solver did not converge in 2 iterations"),
            std::string::npos)
      << result.message;
  EXPECT_NE(result.message.find("DIVERGED_ITS"), std::string::npos) << result.message;
}

TEST(DistLinearSolveTest, SnesViRefusesTheLinearChoice) {
  if (!DistAvailable()) GTEST_SKIP() << "built without PETSc";
  EXPECT_THROW(MakeDistPetscRsls(WithLinear("amg")), std::invalid_argument);
  EXPECT_THROW(MakeDistActiveSet(WithLinear("ilu")), std::invalid_argument);
}

}  // namespace
}  // namespace cb
