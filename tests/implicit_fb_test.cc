// The implicit smoothed-FB formulation: Proposition 3.1, the eta equations, the warm and cold
// starts of docs/method.md section 4, and the Jacobian of (29)-(33) against finite differences.
#include "formulations/implicit_fb/implicit_fb.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fd_check.h"
#include "fixtures.h"
#include "path/path.h"
#include "problems/problem.h"
#include "solvers/condensed_cholesky.h"
#include "solvers/linear_solver.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

TEST(ImplicitFbTest, Proposition31OnAGrid) {
  // psi(a, b, rho) = 0 exactly when a >= 0, b >= 0 and a b = rho^2. The grid values are exact
  // in binary, so a b == rho^2 is decided without rounding.
  int zeros = 0;
  for (double a = -2.0; a <= 2.0; a += 0.25) {
    for (double b = -2.0; b <= 2.0; b += 0.25) {
      for (double rho : {0.0, 0.25, 0.5, 1.0, 1.5}) {
        const bool holds = a >= 0.0 && b >= 0.0 && a * b == rho * rho;
        const double psi = SmoothedFischerBurmeister(a, b, rho);
        if (holds) {
          ++zeros;
          EXPECT_NEAR(psi, 0.0, 1e-14) << a << " " << b << " " << rho;
        } else {
          EXPECT_GT(std::abs(psi), 1e-6) << a << " " << b << " " << rho;
        }
      }
    }
  }
  EXPECT_GT(zeros, 20);
}

TEST(ImplicitFbTest, EtaEquationsHaveTheirCompatibleRoots) {
  for (EtaCase eta : {EtaCase::kCase1, EtaCase::kCase2, EtaCase::kCase3}) {
    for (double gamma : {1.0, 0.3}) {
      const EtaEquation e{eta, gamma};
      for (double m : {-3.0, -1.0, -0.01, 0.0}) {
        const double rho = e.CompatibleRho(m);
        EXPECT_NEAR(e.Value(m, rho), 0.0, 1e-13) << static_cast<int>(eta) << " m=" << m;
      }
      // The only root with m = -rho^2 (every pair at a b = rho^2) is rho = 0 (section 2).
      for (double rho : {0.05, 0.3, 1.0}) EXPECT_NE(e.Value(-rho * rho, rho), 0.0);
      // Analytic derivatives against differences.
      const double h = 1e-6;
      for (double rho : {-0.2, 0.1, 0.7}) {
        const double m = -0.4;
        EXPECT_NEAR(e.DerivativeRho(rho), (e.Value(m, rho + h) - e.Value(m, rho - h)) / (2 * h),
                    1e-7);
        EXPECT_NEAR(e.DerivativeMean(rho), (e.Value(m + h, rho) - e.Value(m - h, rho)) / (2 * h),
                    1e-7);
      }
    }
  }
}

// A model with a few pairs for the start tests.
Problem SmallArch() { return MakeProblem("arch-curved", {{"upper_nodes", "6"}}); }

TEST(ImplicitFbTest, ColdStartRhoMatchesTheReport) {
  // Report section 5.1: g0 = -1, r0 = +1, so -g0^T r0 / nc = 1.
  const Problem p = SmallArch();
  StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(1.0), p.scales};
  StartPoint cold;
  cold.kind = StartKind::kCold;
  const double expected[] = {std::log(2.0), 0.6823278038280193, std::sqrt(0.5)};
  for (int eta = 1; eta <= 3; ++eta) {
    ImplicitFbOptions o;
    o.eta = static_cast<EtaCase>(eta);
    const ImplicitFbStart s = MakeImplicitFbStart(step, cold, o);
    const StepEquationLayout l{p.model->num_dofs(), p.model->num_pairs(), true};
    EXPECT_NEAR(s.x[l.rho()], expected[eta - 1], 1e-12) << "eta case " << eta;
    EXPECT_DOUBLE_EQ(s.gamma, 1.0);
  }
  EXPECT_NEAR(0.6931, std::log(2.0), 1e-4);
  EXPECT_NEAR(0.6823, expected[1], 1e-4);
  EXPECT_NEAR(0.7071, expected[2], 1e-4);
}

// The warm start point satisfies (30), (32) and (33) exactly when |rho*| > rho_ (docs/method.md
// section 4), with gamma = 1 and with gamma < 1.
void ExpectWarmStartSatisfiesRows(double reaction_sign) {
  // A long arch (d >= 1000, so condensed, with the whole Kc factorised: most dofs are contact
  // dofs).
  const Problem p = MakeProblem("arch-curved", {{"upper_nodes", "300"}, {"area_step", "0.0001"}});
  const int d = p.model->num_dofs();
  const int nc = p.model->num_pairs();
  ASSERT_GE(d, 1000);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State base = ZeroState(*p.model);
  for (int i = 0; i < d; ++i) base.u[i] = 0.01 * unit(rng);
  // Reactions: physical (r <= 0) give gamma = 1; wrong-signed, large ones force gamma < 1.
  for (int q = 0; q < nc; ++q)
    base.r[q] = reaction_sign * p.scales.force * (0.5 + std::abs(unit(rng)));
  StepProblem step{p.model.get(), base, StepConstraint::ArcLength(0.1), p.scales};
  StartPoint warm;
  warm.du = Vec::NullaryExpr(d, [&] { return 0.02 * unit(rng); });
  warm.dlambda = 0.3;  // deliberately not on the arc: the start rescales onto it
  warm.r = base.r;
  ImplicitFbOptions o;
  o.eta = EtaCase::kCase1;
  const ImplicitFbStart s = MakeImplicitFbStart(step, warm, o);
  if (reaction_sign > 0) {
    EXPECT_LT(s.gamma, 1.0);
  } else {
    EXPECT_DOUBLE_EQ(s.gamma, 1.0);
  }
  ASSERT_GT(std::abs(s.rho_star), o.rho_min);
  ImplicitFbSystem system(step, EtaEquation{o.eta, s.gamma});
  Vec f;
  ASSERT_TRUE(system.Residual(s.x, &f));
  const StepEquationLayout& l = system.layout();
  EXPECT_LT(f.segment(l.d, nc).lpNorm<Eigen::Infinity>(), 1e-13);  // (30)
  EXPECT_LT(std::abs(f[l.d + 2 * nc]), 1e-13);                     // (32)
  EXPECT_LT(std::abs(f[l.d + 2 * nc + 1]), 1e-13);                 // (33)
}

TEST(ImplicitFbTest, WarmStartSatisfies30_32_33WithGammaOne) { ExpectWarmStartSatisfiesRows(-1.0); }
TEST(ImplicitFbTest, WarmStartSatisfies30_32_33WithGammaBelowOne) {
  ExpectWarmStartSatisfiesRows(+1.0);
}

// Finite-difference check of the full Jacobian of (29)-(33), per eta case and constraint kind,
// at random points of a truss against a flat and a curved obstacle.
struct JacobianCase {
  int eta;
  ConstraintKind kind;
};

// Readable parameters in GoogleTest's messages.
void PrintTo(const JacobianCase& c, std::ostream* out) {
  *out << "eta " << c.eta << ", " << ToString(c.kind);
}

class ImplicitFbJacobianTest : public ::testing::TestWithParam<JacobianCase> {};

TEST_P(ImplicitFbJacobianTest, MatchesFiniteDifferences) {
  const JacobianCase c = GetParam();
  // A long arch (d >= 1000, so condensed, with the whole Kc factorised: most dofs are contact
  // dofs).
  const Problem p = MakeProblem("arch-curved", {{"upper_nodes", "300"}, {"area_step", "0.0001"}});
  const int d = p.model->num_dofs();
  const int nc = p.model->num_pairs();
  ASSERT_GE(d, 1000);
  std::mt19937 rng(11 + c.eta);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State base = ZeroState(*p.model);
  for (int i = 0; i < d; ++i) base.u[i] = 0.05 * unit(rng);
  for (int q = 0; q < nc; ++q) base.r[q] = -std::abs(unit(rng));
  base.lambda = 3.0;
  const StepConstraint constraint = fixtures::ConstraintOf(c.kind, *p.model);
  StepProblem step{p.model.get(), base, constraint, {0.1, 2.0}};
  ImplicitFbSystem system(step, EtaEquation{static_cast<EtaCase>(c.eta), 0.8});
  const StepEquationLayout& l = system.layout();
  Vec x(l.size());
  for (int i = 0; i < l.size(); ++i) x[i] = unit(rng);
  x.segment(0, d) *= 0.05;
  x[l.rho()] = c.eta == 4 ? 0.0 : 0.3;
  SpMat jac;
  system.Jacobian(x, &jac);
  auto residual = [&](const Vec& y) {
    Vec f;
    system.Residual(y, &f);
    return f;
  };
  Mat fd = fd_check::FiniteDifferenceJacobian(residual, x);
  if (c.eta == 4) {
    // rho fixed at 0: F3 is differentiable in g and r away from a = b = 0 but not in rho
    // (|rho| kink); compare every column but rho's.
    fd.col(l.rho()) = Mat(jac).col(l.rho());
  }
  EXPECT_DERIVATIVE_NEAR(Mat(jac), fd, 1e-6);
  // The one-pass evaluation gives the residual and the Jacobian of the two calls bit for bit.
  Vec f_both;
  SpMat jac_both;
  ASSERT_TRUE(system.ResidualAndJacobian(x, &f_both, &jac_both));
  EXPECT_EQ((f_both - residual(x)).norm(), 0.0);
  EXPECT_EQ((Mat(jac_both) - Mat(jac)).norm(), 0.0);
  // A second evaluation elsewhere reuses the pattern and still matches.
  x.segment(0, d) *= -0.5;
  system.Jacobian(x, &jac);
  fd = fd_check::FiniteDifferenceJacobian(residual, x);
  if (c.eta == 4) fd.col(l.rho()) = Mat(jac).col(l.rho());
  EXPECT_DERIVATIVE_NEAR(Mat(jac), fd, 1e-6);
}

std::vector<JacobianCase> AllJacobianCases() {
  std::vector<JacobianCase> cases;
  for (int eta = 1; eta <= 4; ++eta) {
    for (ConstraintKind k : fixtures::kAllConstraintKinds) {
      cases.push_back({eta, k});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EtaAndConstraint, ImplicitFbJacobianTest,
                         ::testing::ValuesIn(AllJacobianCases()),
                         [](const ::testing::TestParamInfo<JacobianCase>& info) {
                           std::string kind = ToString(info.param.kind);
                           for (char& ch : kind) {
                             if (ch == '-') ch = '_';
                           }
                           return "eta" + std::to_string(info.param.eta) + "_" + kind;
                         });

TEST(ImplicitFbTest, NonsmoothCaseHasAFiniteJacobianAtTheDegeneratePoint) {
  const Problem p = MakeProblem("bar-wall");
  StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(1.0), p.scales};
  ImplicitFbSystem system(step, EtaEquation{EtaCase::kNonsmooth, 1.0});
  Vec x = Vec::Zero(system.size());  // g = r = rho = 0: psi is not differentiable here
  SpMat jac;
  system.Jacobian(x, &jac);
  EXPECT_TRUE(Mat(jac).allFinite());
}

// P1 (n = 50) from the report's cold start, eta cases 1 and 2, Newton and dogleg: verified.
class BlockColdSolveTest : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

TEST_P(BlockColdSolveTest, IsVerified) {
  const auto [eta, solver] = GetParam();
  const Problem p = MakeProblem("block");
  ImplicitFbOptions o;
  o.eta = static_cast<EtaCase>(eta);
  o.solver = solver;
  ImplicitFb formulation(o);
  const fixtures::JudgedSolve a = fixtures::SolveAndJudge(p, formulation, 1.0, StartKind::kCold);
  const PathSummary& s = a.summary;
  const Verdict& v = a.verdict;
  EXPECT_EQ(s.status, Status::kConverged) << s.message;
  EXPECT_TRUE(v.verified) << v.eq_res << " " << v.comp_res << " " << v.feas_res;
  // Equilibrium of the whole body: the wall and the floor carry the 10 kN load components.
  const Vec& r = s.final_state.r;
  EXPECT_NEAR(r.head(51).sum(), -1e4, 1e-4);  // wall pairs, reaction along -x normal
  EXPECT_NEAR(r.tail(51).sum(), -1e4, 1e-4);  // floor pairs
}

INSTANTIATE_TEST_SUITE_P(EtaAndSolver, BlockColdSolveTest,
                         ::testing::Combine(::testing::Values(1, 2),
                                            ::testing::Values("newton", "dogleg")),
                         [](const ::testing::TestParamInfo<std::tuple<int, std::string>>& info) {
                           return "eta" + std::to_string(std::get<0>(info.param)) + "_" +
                                  std::get<1>(info.param);
                         });

// P1 from the cold start over every mesh n = 10..50: the same physics, so Newton's iteration
// count must not depend on the mesh's luck. With a monotone line search it ranged from 13 to 55
// (n = 10, eta 1), the full step clipped to the minimum factor for dozens of iterations.
TEST(BlockColdSolve, TakesAtMostTwentyNewtonIterationsOnEveryMesh) {
  for (int n = 10; n <= 50; ++n) {
    const Problem p = MakeProblem("block", {{"n", std::to_string(n)}});
    const StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(1.0),
                           p.scales};
    StartPoint cold;
    cold.kind = StartKind::kCold;
    for (const EtaCase eta : {EtaCase::kCase1, EtaCase::kCase2}) {
      ImplicitFbOptions o;
      o.eta = eta;
      o.solver = "newton";
      ImplicitFb formulation(o);
      const StepResult result = formulation.Solve(step, cold);
      const std::string where =
          "n = " + std::to_string(n) + ", eta " + std::to_string(static_cast<int>(eta));
      EXPECT_EQ(result.status, Status::kConverged) << where << ": " << result.message;
      EXPECT_LE(result.counts.iterations, 20) << where;
      EXPECT_TRUE(Judge(step, result.point, 1e-8).verified) << where;
    }
  }
}

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
// The condensed Newton step ("cholmod": elimination of g and r, Cholesky of the stiffness plus
// the pair springs, border by block elimination, refinement on the full system) equals the
// full-system LU step up to rounding, along the iterates of a solve (far from and close to the
// answer, where closed pairs have dF3/dr -> 0 and their springs are capped).
void ExpectCondensedStepsMatchFullSteps(const StepProblem& step, const StartPoint& start,
                                        EtaCase eta, bool expect_condensed) {
  ImplicitFbOptions o;
  o.eta = eta;
  const ImplicitFbStart initial = MakeImplicitFbStart(step, start, o);
  ImplicitFbSystem system(step, EtaEquation{eta, initial.gamma});
  auto condensed = MakeLinearSolver("cholmod");
  auto lu = MakeLinearSolver("klu");
  condensed->SetStructure(system.structure());
  ASSERT_NE(system.structure(), nullptr);
  Vec x = initial.x, f, dx, dx_lu;
  SpMat jac;
  int compared = 0;
  for (int k = 0; k < 40; ++k) {
    system.Residual(x, &f);
    if (f.cwiseAbs().maxCoeff() < 1e-11) break;
    system.Jacobian(x, &jac);
    if (!jac.coeffs().allFinite()) break;
    ASSERT_TRUE(lu->Factorize(jac)) << "iterate " << k << ": " << lu->message();
    ASSERT_TRUE(lu->Solve(f, &dx_lu));
    ASSERT_TRUE(condensed->Factorize(jac)) << condensed->message();
    ASSERT_TRUE(condensed->Solve(f, &dx)) << condensed->message();
    // The same step up to rounding: the condensed step solves the full system at least as
    // accurately as the LU or to the refinement's target (a backward error of 1e-13, far below
    // what a Newton step needs), and where the LU's own residual shows a well-conditioned system
    // the two steps agree to that accuracy times cond(J) (on the ill-conditioned iterates of the
    // long arch both carry errors of about eps cond(J), and the LU's residual is the larger).
    // Normwise backward errors ||J dx - f|| / (||J|| ||dx|| + ||f||), inf-norms.
    Vec row_sums = Vec::Zero(jac.rows());
    for (int j = 0; j < jac.outerSize(); ++j) {
      for (SpMat::InnerIterator it(jac, j); it; ++it) row_sums[it.row()] += std::abs(it.value());
    }
    const double jac_norm = row_sums.maxCoeff();
    auto backward = [&](const Vec& step) {
      return (jac * step - f).lpNorm<Eigen::Infinity>() /
             (jac_norm * step.lpNorm<Eigen::Infinity>() + f.lpNorm<Eigen::Infinity>());
    };
    const double omega = backward(dx), omega_lu = backward(dx_lu);
    EXPECT_LE(omega, std::max(4.0 * omega_lu, 1e-13)) << "iterate " << k;
    const double res_lu = (jac * dx_lu - f).norm() / f.norm();
    if (res_lu <= 1e-13) {
      EXPECT_LE((dx - dx_lu).norm(), 1e-7 * dx_lu.norm() + 1e-13 * (1.0 + x.norm()))
          << "iterate " << k;
    }
    ++compared;
    // Newton steps, damped to at most 0.5 in any unknown (far from the answer full steps can
    // leave the region where the model is defined).
    x -= std::min(1.0, 0.5 / dx_lu.lpNorm<Eigen::Infinity>()) * dx_lu;
  }
  EXPECT_GE(compared, 3);
  const CondensedSolverStats* stats = CondensedStats(*condensed);
  ASSERT_NE(stats, nullptr);
  if (expect_condensed) {
    EXPECT_EQ(stats->condensed_factorizations, compared);
    EXPECT_EQ(stats->fallback_solves, 0);
  } else {
    EXPECT_GT(stats->condensed_factorizations + stats->fallback_factorizations, 0);
  }
}

TEST(ImplicitFbCondensedTest, BlockColdStartStepsMatch) {
  // n = 25 (d = 1352, 52 contact dofs): the contact-block path; n = 8 (d = 162): the LU.
  for (const char* n : {"8", "25"}) {
    const Problem p = MakeProblem("block", {{"n", n}});
    StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(1.0), p.scales};
    StartPoint cold;
    cold.kind = StartKind::kCold;
    for (EtaCase eta : {EtaCase::kCase1, EtaCase::kNonsmooth}) {
      SCOPED_TRACE(std::string("n = ") + n + ", eta " + std::to_string(static_cast<int>(eta)));
      ExpectCondensedStepsMatchFullSteps(step, cold, eta, p.model->num_dofs() >= 1000);
    }
  }
}

TEST(ImplicitFbCondensedTest, CurvedArchStepsMatchForEveryConstraint) {
  // The curved obstacle adds the curvature term to the stiffness; a warm start from a state in
  // contact. The kink row makes one pair's spring negative: condensed or fallback, the step is
  // the same.
  // A long arch (d >= 1000, so condensed, with the whole Kc factorised: most dofs are contact
  // dofs).
  const Problem p = MakeProblem("arch-curved", {{"upper_nodes", "300"}, {"area_step", "0.0001"}});
  const int d = p.model->num_dofs();
  const int nc = p.model->num_pairs();
  ASSERT_GE(d, 1000);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State base = ZeroState(*p.model);
  for (int i = 0; i < d; ++i) base.u[i] = 0.02 * unit(rng);
  for (int q = 0; q < nc; ++q) base.r[q] = q % 2 == 0 ? -std::abs(unit(rng)) : 0.0;
  base.lambda = 3.0;
  for (ConstraintKind kind : fixtures::kAllConstraintKinds) {
    SCOPED_TRACE(ToString(kind));
    StepProblem step{p.model.get(), base, fixtures::ConstraintOf(kind, *p.model), {0.1, 2.0}};
    StartPoint warm;
    warm.du = Vec::Constant(d, 0.001);
    warm.dlambda = 0.05;
    warm.r = base.r;
    ExpectCondensedStepsMatchFullSteps(step, warm, EtaCase::kCase1, kind != ConstraintKind::kKink);
  }
}
#endif

}  // namespace
}  // namespace cb
