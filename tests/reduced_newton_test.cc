// The reduced Newton of implicit-fb (option reduced_newton; formulations/common/
// reduced_step_system.h): the same verified answer as the full route on P1, hertz-3d and a Q4
// file; Hertz's closed form; the interior rows of (29) exact at every iterate; its Jacobian
// against differences; and the refusal of steps it does not apply to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fd_check.h"
#include "fixtures.h"
#include "formulations/common/reduced_step_system.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "io/problem_file.h"
#include "path/path.h"
#include "problems/hertz.h"
#include "problems/problem.h"
#include "refusal.h"
#include "solvers/newton.h"
#include "source_tree.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

ImplicitFbOptions Reduced() {
  ImplicitFbOptions o;
  o.reduced_newton = true;
  return o;
}

// Both routes verified, and the same u and r to `tol` relative to their sizes.
void ExpectSameAnswer(const Problem& p, StartKind start, double tol) {
  ImplicitFb full_route;
  ImplicitFb reduced_route(Reduced());
  const fixtures::JudgedSolve full = fixtures::SolveAndJudge(p, full_route, p.load, start);
  const fixtures::JudgedSolve reduced = fixtures::SolveAndJudge(p, reduced_route, p.load, start);
  ASSERT_EQ(full.summary.status, Status::kConverged) << full.summary.message;
  ASSERT_EQ(reduced.summary.status, Status::kConverged) << reduced.summary.message;
  EXPECT_TRUE(reduced.verdict.verified)
      << reduced.verdict.eq_res << " " << reduced.verdict.comp_res;
  const State& a = full.summary.final_state;
  const State& b = reduced.summary.final_state;
  EXPECT_LE((a.u - b.u).lpNorm<Eigen::Infinity>(), tol * a.u.lpNorm<Eigen::Infinity>());
  EXPECT_LE((a.r - b.r).lpNorm<Eigen::Infinity>(), tol * a.r.lpNorm<Eigen::Infinity>());
}

TEST(ReducedNewtonTest, SameAnswerAsTheFullRouteOnP1) {
  // n = 10: the simplicial elimination; n = 40: the contact-block factor (d > 1000).
  for (const char* n : {"10", "40"}) {
    const Problem p = MakeProblem("block", {{"n", n}});
    for (StartKind start : {StartKind::kWarm, StartKind::kCold}) {
      SCOPED_TRACE(std::string("n = ") + n);
      ExpectSameAnswer(p, start, 1e-7);
    }
  }
}

TEST(ReducedNewtonTest, SameAnswerAsTheFullRouteOnHertz3d) {
  const Problem p = MakeProblem("hertz-3d", {{"n", "6"}, {"nz", "6"}});
  ExpectSameAnswer(p, StartKind::kWarm, 1e-7);
}

TEST(ReducedNewtonTest, SameAnswerAsTheFullRouteOnAQ4File) {
  const Problem p = io::LoadProblemFile(
      (testing_support::SourceRoot() / "examples" / "q4-block-on-floor.json").string());
  ExpectSameAnswer(p, StartKind::kWarm, 1e-7);
}

// docs/problems.md: on the 8 x 8 x 8 mesh the contact radius and the peak pressure are within
// 3 % of Hertz's, and the sphere carries the quarter load.
TEST(ReducedNewtonTest, HertzClosedForm) {
  const Problem p = MakeProblem("hertz-3d", {{"n", "8"}, {"nz", "8"}});
  ImplicitFb formulation(Reduced());
  const fixtures::JudgedSolve a = fixtures::SolveAndJudge(p, formulation, p.load);
  ASSERT_EQ(a.summary.status, Status::kConverged) << a.summary.message;
  EXPECT_TRUE(a.verdict.verified);
  EXPECT_NEAR(a.summary.final_state.r.sum(), -7.5, 1e-8);
  const HertzContact exact = HertzClosedForm(30.0, 50.0, 1000.0, 0.3);
  const HertzContact measured = MeasureHertzContact(p, a.summary.final_state.r);
  EXPECT_NEAR(measured.radius / exact.radius, 1.0, 0.03);
  EXPECT_NEAR(measured.peak_pressure / exact.peak_pressure, 1.0, 0.03);
}

// Implicit-fb's step of `p` to lambda = 1 from the unloaded state (eta case 1), its cold start
// and its reduced system (not yet prepared).
struct ColdReducedStep {
  explicit ColdReducedStep(const Problem& p)
      : step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(1.0), p.scales},
        start(MakeImplicitFbStart(step, Cold(), ImplicitFbOptions{})),
        system(step, EtaEquation{EtaCase::kCase1, start.gamma}),
        reduced(system) {}
  static StartPoint Cold() {
    StartPoint cold;
    cold.kind = StartKind::kCold;
    return cold;
  }
  StepProblem step;
  ImplicitFbStart start;
  ImplicitFbSystem system;
  ReducedStepSystem reduced;
};

// The largest |row| of (29) / R on the interior dofs at the full x, and the largest term there.
double InteriorResidual(StepEquationSystem& system, const std::vector<int>& contact_dofs,
                        const Vec& x) {
  Vec f;
  EXPECT_TRUE(system.Residual(x, &f));
  std::vector<bool> contact(system.layout().d, false);
  for (int dof : contact_dofs) contact[dof] = true;
  double worst = 0.0;
  for (int i = 0; i < system.layout().d; ++i) {
    if (!contact[i]) worst = std::max(worst, std::abs(f[i]));
  }
  return worst;
}

// The method's property: every iterate, with its interior recovered, satisfies the interior
// rows of (29) to rounding; the cold start's full point does not (so the check can fail).
TEST(ReducedNewtonTest, InteriorRowsHoldAtEveryIterate) {
  for (const char* n : {"10", "40"}) {
    const Problem p = MakeProblem("block", {{"n", n}});
    ColdReducedStep cold(p);
    ImplicitFbSystem& system = cold.system;
    ReducedStepSystem& reduced = cold.reduced;
    const ImplicitFbStart& start = cold.start;
    ASSERT_TRUE(reduced.Prepare(start.x));
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
    // n = 10 (242 dofs) takes the simplicial elimination, n = 40 the contact-block factor.
    EXPECT_EQ(reduced.elimination().uses_contact_block(), std::string(n) == "40");
#endif
    const std::vector<int>& c = reduced.elimination().contact_dofs();
    EXPECT_GT(InteriorResidual(system, c, start.x), 1e-3);
    // The size of the interior rows' terms: the load over R.
    const double scale = p.model->load_pattern().lpNorm<Eigen::Infinity>() / p.scales.force;
    NewtonSolver solver(SolverOptions{});
    Vec z = reduced.Reduce(start.x);
    int iterates = 0;
    double worst = 0.0;
    solver.Solve(reduced, &z, [&](const IterationInfo& info) {
      Vec x;
      EXPECT_TRUE(reduced.Expand(*info.x, &x));
      worst = std::max(worst, InteriorResidual(system, c, x));
      ++iterates;
      return true;
    });
    EXPECT_GT(iterates, 2);
    EXPECT_LE(worst, 1e-11 * std::max(1.0, scale)) << "n = " << n;
  }
}

TEST(ReducedNewtonTest, JacobianMatchesFiniteDifferences) {
  const Problem p = MakeProblem("hertz-3d", {{"n", "4"}, {"nz", "3"}});
  ColdReducedStep cold(p);
  ReducedStepSystem& reduced = cold.reduced;
  ASSERT_TRUE(reduced.Prepare(cold.start.x));
  Vec z = reduced.Reduce(cold.start.x);
  // Away from the start's symmetric point: some displacement and mixed contact values.
  for (int k = 0; k < z.size(); ++k) z[k] += 1e-3 * std::sin(1.0 + k);
  SpMat j;
  reduced.Jacobian(z, &j);
  const Mat fd = fd_check::FiniteDifferenceJacobian(
      [&](const Vec& y) {
        Vec f;
        EXPECT_TRUE(reduced.Residual(y, &f));
        return f;
      },
      z);
  const Mat analytic = Mat(j);
  EXPECT_LE((analytic - fd).lpNorm<Eigen::Infinity>(),
            1e-6 * std::max(1.0, analytic.lpNorm<Eigen::Infinity>()));
}

TEST(ReducedNewtonTest, RefusesArcLengthStepsNamingTheOption) {
  const Problem p = MakeProblem("block", {{"n", "10"}});
  StepConstraint arc = StepConstraint::ArcLength(0.1, 1.0);
  const StepProblem step{p.model.get(), ZeroState(*p.model), arc, p.scales};
  ImplicitFb reduced(Reduced());
  std::string why;
  EXPECT_FALSE(reduced.Accepts(step, &why));
  EXPECT_TRUE(testing_support::Names(why, {"reduced_newton"}));
  EXPECT_TRUE(ImplicitFb().Accepts(step));
}

}  // namespace
}  // namespace cb
