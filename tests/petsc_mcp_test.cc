// The step as PETSc's mixed complementarity problem (formulations/petsc/petsc_mcp.h), in every
// build (no PETSc needed): the MCP function's Jacobian against finite differences for every
// step constraint, its rows as the combination of the shared step equations, the bounds, the
// starts inside them, the natural residual, and the compressed-row map (diagonal included).
#include "formulations/petsc/petsc_mcp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "fd_check.h"
#include "fixtures.h"
#include "problems/problem.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

// Steps of the two-bar truss over its floor (a curved path, one pair) and of P1 at n = 2
// (linear, many pairs), from a state off the path, with every kind of step constraint.
std::vector<StepProblem> Steps(const Problem& truss, const Problem& block) {
  State truss_base = ZeroState(*truss.model);
  truss_base.u.setConstant(0.01);
  truss_base.lambda = 0.1;
  const State block_base = ZeroState(*block.model);
  return {
      {truss.model.get(), truss_base, StepConstraint::ArcLength(0.05), truss.scales},
      {truss.model.get(), truss_base, StepConstraint::FixedLoad(0.3), truss.scales},
      {truss.model.get(), truss_base, StepConstraint::Displacement(truss.control_dof, -0.05),
       truss.scales},
      {truss.model.get(), truss_base, StepConstraint::Kink(0), truss.scales},
      {block.model.get(), block_base, StepConstraint::FixedLoad(block.load), block.scales},
      {block.model.get(), block_base, StepConstraint::Kink(1), block.scales},
  };
}

Vec RandomPoint(int size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  Vec x(size);
  for (int i = 0; i < size; ++i) x[i] = unit(rng);
  return x;
}

TEST(PetscMcpTest, TheJacobianIsTheFiniteDifferenceOfTheFunctionForEveryConstraint) {
  const Problem truss = MakeProblem("two-bar-obstacle");
  const Problem block = MakeProblem("block", {{"n", "2"}});
  unsigned seed = 1;
  for (const StepProblem& step : Steps(truss, block)) {
    McpStepEquations equations(step);
    const Vec x = RandomPoint(equations.size(), seed++);
    SpMat s;
    equations.Jacobian(x, &s);
    const McpRowMap map = MakeMcpRowMap(equations.layout(), s);
    auto f = [&](const Vec& y) {
      Vec out;
      McpFunction(equations, y, &out);
      return out;
    };
    SCOPED_TRACE(std::string(ToString(step.constraint.kind)) + " on " +
                 std::to_string(step.num_dofs()) + " dofs");
    EXPECT_DERIVATIVE_NEAR(Mat(McpJacobian(map, s)), fd_check::FiniteDifferenceJacobian(f, x),
                           1e-6);
  }
}

TEST(PetscMcpTest, ThePairsRowsAreTheContactConditionPlusThirtyAndThirty) {
  const Problem block = MakeProblem("block", {{"n", "2"}});
  const StepProblem step{block.model.get(), ZeroState(*block.model),
                         StepConstraint::FixedLoad(block.load), block.scales};
  McpStepEquations equations(step);
  const StepEquationLayout& l = equations.layout();
  const Vec x = RandomPoint(l.size(), 7);
  Vec f;
  ASSERT_TRUE(McpFunction(equations, x, &f));
  Vec phi;
  block.model->Gaps(step.base.u + x.segment(l.du(), l.d), &phi);
  for (int p = 0; p < l.nc; ++p) {
    const double thirty = x[l.g() + p] + phi[p] / step.scales.length;  // (30) / L
    EXPECT_NEAR(f[l.r() + p], thirty, 1e-14);
    EXPECT_NEAR(f[l.g() + p], -x[l.r() + p] + thirty, 1e-14);
  }
}

TEST(PetscMcpTest, OnlyTheGapsAreBoundedAndTheKinkPairIsFree) {
  const Problem block = MakeProblem("block", {{"n", "2"}});
  StepProblem step{block.model.get(), ZeroState(*block.model),
                   StepConstraint::FixedLoad(block.load), block.scales};
  const StepEquationLayout l{step.num_dofs(), step.num_pairs(), false};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  McpBounds b = MakeMcpBounds(step);
  for (int i = 0; i < l.size(); ++i) {
    const bool gap = i >= l.g() && i < l.g() + l.nc;
    EXPECT_EQ(b.lower[i], gap ? 0.0 : -kInf) << i;
    EXPECT_EQ(b.upper[i], kInf) << i;
  }
  step.constraint = StepConstraint::Kink(2);
  b = MakeMcpBounds(step);
  EXPECT_EQ(b.lower[l.g() + 2], -kInf);
  EXPECT_EQ(b.lower[l.g() + 1], 0.0);
}

TEST(PetscMcpTest, TheStartsLieInTheBounds) {
  const Problem truss = MakeProblem("two-bar-obstacle");
  State base = ZeroState(*truss.model);
  base.r.setConstant(-2.0);
  const StepProblem step{truss.model.get(), base, StepConstraint::ArcLength(0.05), truss.scales};
  const StepEquationLayout l{step.num_dofs(), step.num_pairs(), false};
  const McpBounds bounds = MakeMcpBounds(step);
  StartPoint start;
  start.kind = StartKind::kCold;
  start.du = Vec::Zero(l.d);
  start.r = base.r;
  const Vec cold = MakeMcpStart(step, start, bounds);
  EXPECT_EQ(cold.segment(l.g(), l.nc), Vec::Zero(l.nc));            // g^0 = -1 projected
  EXPECT_EQ(cold.segment(l.r(), l.nc), Vec::Constant(l.nc, -1.0));  // every pair closed
  EXPECT_EQ(cold.segment(l.du(), l.d), Vec::Zero(l.d));
  EXPECT_NEAR(StepConstraintValue(step, cold.segment(0, l.d), cold[l.dlambda()], Vec(), Vec()), 0.0,
              1e-14);
  // Warm, with a predictor that penetrates the floor (a fixed-load step keeps it as it is):
  // g^0 clipped to 0, r^0 = r^k / R.
  const StepProblem fixed{truss.model.get(), base, StepConstraint::FixedLoad(0.1), truss.scales};
  start.kind = StartKind::kWarm;
  start.du = Vec::Zero(l.d);
  start.du[truss.control_dof] = -10.0;
  start.dlambda = 0.0;
  const Vec warm = MakeMcpStart(fixed, start, bounds);
  EXPECT_TRUE((warm.array() >= bounds.lower.array()).all());
  EXPECT_EQ(warm[l.g()], 0.0);
  EXPECT_EQ(warm[l.r()], -2.0 / step.scales.force);
}

TEST(PetscMcpTest, AWarmStartPutsThePairsClosedAtTheKnownStateAtTheirBound) {
  // The truss at its zero state, clear of the floor: the predictor's gap g^ = -phi / L > 0.
  const Problem truss = MakeProblem("two-bar-obstacle");
  State base = ZeroState(*truss.model);
  const StepProblem open{truss.model.get(), base, StepConstraint::FixedLoad(0.1), truss.scales};
  const StepEquationLayout l{open.num_dofs(), open.num_pairs(), false};
  const McpBounds bounds = MakeMcpBounds(open);
  Vec phi;
  truss.model->Gaps(base.u, &phi);
  ASSERT_GT(-phi[0], 0.0);
  StartPoint start;
  start.du = Vec::Zero(l.d);
  start.r = base.r;
  EXPECT_EQ(MakeMcpStart(open, start, bounds)[l.g()], -phi[0] / truss.scales.length);
  // The same predictor from a state where the pair carries a reaction: it starts at g^ = 0, so
  // that RSLS, which takes a bound as active only within 1e-8 of it, starts with it closed.
  base.r.setConstant(-2.0);
  start.r = base.r;
  const StepProblem closed{truss.model.get(), base, StepConstraint::FixedLoad(0.1), truss.scales};
  const Vec x = MakeMcpStart(closed, start, bounds);
  EXPECT_EQ(x[l.g()], 0.0);
  EXPECT_EQ(x[l.r()], -2.0 / truss.scales.force);
  // A reaction the verdict cannot tell from zero does not close the pair.
  base.r.setConstant(-0.1 * kTieReaction * truss.scales.force);
  start.r = base.r;
  const StepProblem tiny{truss.model.get(), base, StepConstraint::FixedLoad(0.1), truss.scales};
  EXPECT_EQ(MakeMcpStart(tiny, start, bounds)[l.g()], -phi[0] / truss.scales.length);
}

TEST(PetscMcpTest, AWarmStartSendsTiesToTheClosedSide) {
  // P1's pairs touch their obstacles at the zero state with no reaction: every one a tie.
  const Problem block = MakeProblem("block", {{"n", "2"}});
  const StepProblem step{block.model.get(), ZeroState(*block.model),
                         StepConstraint::FixedLoad(block.load), block.scales};
  const StepEquationLayout l{step.num_dofs(), step.num_pairs(), false};
  StartPoint start;
  start.du = Vec::Zero(l.d);
  start.r = Vec::Zero(l.nc);
  const McpBounds bounds = MakeMcpBounds(step);
  const Vec x = MakeMcpStart(step, start, bounds);
  EXPECT_EQ(x.segment(l.g(), l.nc), Vec::Zero(l.nc));
  EXPECT_EQ(x.segment(l.r(), l.nc), Vec::Constant(l.nc, -kTieReaction));
  // F2 = -r^ + (30) > 0 at the bound: SNESVI counts the pairs as closed.
  McpStepEquations equations(step);
  Vec f;
  ASSERT_TRUE(McpFunction(equations, x, &f));
  EXPECT_TRUE((f.segment(l.g(), l.nc).array() > 0.0).all());
}

TEST(PetscMcpTest, TheNaturalResidualVanishesExactlyAtComplementarity) {
  McpBounds b{Vec::Constant(3, 0.0), Vec::Constant(3, std::numeric_limits<double>::infinity())};
  Vec x(3), f(3);
  x << 0.0, 2.0, 0.0;
  f << 3.0, 0.0, 0.0;  // at the bound with F >= 0, inside with F = 0, degenerate
  EXPECT_EQ(McpNaturalResidual(x, f, b), 0.0);
  f[0] = -0.25;  // at the bound pushing outward
  EXPECT_EQ(McpNaturalResidual(x, f, b), 0.25);
  f[0] = 0.0;
  f[1] = 0.5;  // inside with F != 0: mid(2, 0.5, -inf) = 0.5
  EXPECT_EQ(McpNaturalResidual(x, f, b), 0.5);
}

TEST(PetscMcpTest, TheRowMapStoresEveryDiagonalAndKnowsItsPattern) {
  const Problem block = MakeProblem("block", {{"n", "2"}});
  const StepProblem step{block.model.get(), ZeroState(*block.model),
                         StepConstraint::Displacement(0, 1e-3), block.scales};
  McpStepEquations equations(step);
  SpMat s;
  equations.Jacobian(RandomPoint(equations.size(), 3), &s);
  const McpRowMap map = MakeMcpRowMap(equations.layout(), s);
  ASSERT_EQ(map.row_start.size(), static_cast<std::size_t>(map.size) + 1);
  for (int i = 0; i < map.size; ++i) {
    bool diagonal = false;
    for (int k = map.row_start[i]; k < map.row_start[i + 1]; ++k) {
      if (k > map.row_start[i]) {
        EXPECT_LT(map.columns[k - 1], map.columns[k]) << i;
      }
      diagonal = diagonal || map.columns[k] == i;
    }
    EXPECT_TRUE(diagonal) << "row " << i;
  }
  EXPECT_TRUE(SamePattern(map, s));
  SpMat other = s;
  other.coeffRef(0, map.size - 1) = 1.0;  // a new entry: another pattern
  other.makeCompressed();
  EXPECT_FALSE(SamePattern(map, other));
}

}  // namespace
}  // namespace cb
