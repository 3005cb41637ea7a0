// The verdict (docs/method.md section 7) on points whose residuals are known.
#include "verdict/verdict.h"

#include <gtest/gtest.h>

#include "path/path.h"
#include "problems/problem.h"

namespace cb {
namespace {

// The bar against the wall at lambda = 2 (in contact): u = gap, r = -(2 - EA gap / L).
struct BarAtTwo {
  Problem p = MakeProblem("bar-wall");
  StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(2.0), p.scales};
  StepPoint exact() const {
    StepPoint x;
    x.du = Vec::Zero(p.model->num_dofs());
    x.du[p.control_dof] = 0.01;
    x.r = Vec::Constant(1, -(2.0 - 100.0 * 0.01 / 1.0));
    x.g = Vec::Zero(1);
    x.dlambda = 2.0;
    return x;
  }
};

TEST(VerdictTest, ExactSolutionIsVerified) {
  BarAtTwo b;
  const Verdict v = Judge(b.step, b.exact(), 1e-8);
  EXPECT_TRUE(v.verified);
  EXPECT_LT(v.eq_res, 1e-14);
  EXPECT_LT(v.comp_res, 1e-14);
  EXPECT_EQ(v.feas_res, 0.0);
  EXPECT_EQ(v.step_res, 0.0);
}

TEST(VerdictTest, EachResidualCatchesItsOwnDefect) {
  BarAtTwo b;
  StepPoint x = b.exact();
  x.r[0] *= 1.001;  // unbalanced
  EXPECT_GT(Judge(b.step, x, 1e-8).eq_res, 1e-6);
  EXPECT_FALSE(Judge(b.step, x, 1e-8).verified);

  x = b.exact();
  x.du[b.p.control_dof] = 0.0105;  // penetrates the wall by 0.5 mm: g = -5e-4
  const Verdict pen = Judge(b.step, x, 1e-8);
  EXPECT_NEAR(pen.feas_res, 5e-4 / b.p.scales.length, 1e-12);
  EXPECT_FALSE(pen.verified);

  x = b.exact();
  x.r[0] = 0.5;  // adhesion
  const Verdict adh = Judge(b.step, x, 1e-8);
  EXPECT_NEAR(adh.feas_res, 0.5 / b.p.scales.force, 1e-12);

  x = b.exact();
  x.dlambda = 2.5;  // violates the fixed-load constraint
  EXPECT_NEAR(Judge(b.step, x, 1e-8).step_res, 0.5, 1e-12);
}

TEST(VerdictTest, ComplementarityIsJudgedInScaledUnits) {
  // An open gap of 1e-3 with a reaction of -1e-2 violates g r = 0 by min(g/L, -r/R).
  BarAtTwo b;
  StepPoint x;
  x.du = Vec::Zero(b.p.model->num_dofs());
  x.r = Vec::Constant(1, -1e-2);
  x.dlambda = 0.0;
  StepProblem step{b.p.model.get(), ZeroState(*b.p.model), StepConstraint::FixedLoad(0.0),
                   b.p.scales};
  const Verdict v = Judge(step, x, 1e-8);
  EXPECT_NEAR(v.comp_res, std::min(0.01 / b.p.scales.length, 1e-2 / b.p.scales.force), 1e-15);
}

TEST(VerdictTest, NonFiniteNeverVerifies) {
  BarAtTwo b;
  StepPoint x = b.exact();
  x.r[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(Judge(b.step, x, 1e-8).verified);
}

}  // namespace
}  // namespace cb
