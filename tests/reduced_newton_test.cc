// The reduced Newton of implicit-fb (option reduced_newton; formulations/common/
// reduced_step_system.h): the same verified answer as the full route on P1, hertz-3d and a Q4
// file; Hertz's closed form; the interior rows of (29) exact at every iterate; its Jacobian
// against differences; its condensed block factorised by the condensed route whatever its size;
// the time split it reports; the default (reduced where it applies, the full route elsewhere)
// and the refusal, when it is required, of steps it does not apply to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
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
#include "solvers/condensed_cholesky.h"
#include "solvers/linear_solver.h"
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

ImplicitFbOptions Full() {
  ImplicitFbOptions o;
  o.reduced_newton = false;
  return o;
}

// Both routes verified, and the same u and r to `tol` relative to their sizes.
void ExpectSameAnswer(const Problem& p, StartKind start, double tol) {
  ImplicitFb full_route(Full());
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
  EXPECT_TRUE(ImplicitFb(Full()).Accepts(step));
}

// One solve of `step` by `formulation` from the cold start.
StepResult SolveCold(ImplicitFb& formulation, const StepProblem& step) {
  return formulation.Solve(step, ColdReducedStep::Cold(), SolveControls{});
}

// By default the fixed-load step takes the reduced route and an arc-length step the full one;
// reduced_newton = false takes the full route on both. Each answer verified.
TEST(ReducedNewtonTest, DefaultIsReducedWhereItApplies) {
  const Problem p = MakeProblem("block", {{"n", "10"}});
  const StepProblem fixed{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load),
                          p.scales};
  const StepProblem arc{p.model.get(), ZeroState(*p.model), StepConstraint::ArcLength(0.1, 1.0),
                        p.scales};
  auto route = [](const StepResult& r) {
    return r.details.count("route") != 0 && r.details.at("route") == "reduced";
  };
  ImplicitFb by_default, full(Full());
  const StepResult a = SolveCold(by_default, fixed);
  ASSERT_EQ(a.status, Status::kConverged) << a.message;
  EXPECT_TRUE(route(a));
  EXPECT_TRUE(Judge(fixed, a.point, 1e-8).verified);
  const StepResult b = SolveCold(full, fixed);
  ASSERT_EQ(b.status, Status::kConverged) << b.message;
  EXPECT_FALSE(route(b));
  EXPECT_TRUE(Judge(fixed, b.point, 1e-8).verified);
  const StepResult c = SolveCold(by_default, arc);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  EXPECT_FALSE(route(c));
}

// hertz-3d with E = 1e14 from the warm start of `contactbench run` (the unloaded state): the
// reduced route alone stagnates (the interior's rounding at that scale); by default the full
// route then solves the step from the same start, its counts added to the reduced route's, and
// its message says so.
TEST(ReducedNewtonTest, FallsBackToTheFullRouteWhereTheReducedOneFails) {
  const Problem p = MakeProblem("hertz-3d", {{"n", "8"}, {"nz", "8"}, {"youngs_modulus", "1e14"}});
  const StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load),
                         p.scales};
  StartPoint warm;
  warm.du = Vec::Zero(step.num_dofs());
  warm.dlambda = p.load;
  warm.r = Vec::Zero(step.num_pairs());
  ImplicitFb required(Reduced()), by_default;
  const StepResult alone = required.Solve(step, warm, SolveControls{});
  ASSERT_FALSE(alone.status == Status::kConverged && Judge(step, alone.point, 1e-8).verified)
      << "the case no longer makes the reduced route fail: " << alone.message;
  const StepResult r = by_default.Solve(step, warm, SolveControls{});
  ASSERT_EQ(r.status, Status::kConverged) << r.message;
  EXPECT_TRUE(Judge(step, r.point, 1e-8).verified);
  EXPECT_EQ(r.details.at("route"), "full after reduced");
  EXPECT_GT(r.counts.iterations, alone.counts.iterations);
  // One history for the step, numbered as its counts: 1, 2, ... through both routes.
  ASSERT_EQ(r.history.size(), static_cast<std::size_t>(r.counts.iterations));
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    EXPECT_EQ(r.history[k].iteration, static_cast<int>(k) + 1) << "record " << k;
  }
  EXPECT_TRUE(testing_support::Names(r.message, {"full route", "reduced Newton"})) << r.message;
}

// The time split of a reduced solve: each piece present, non-negative, the factorisation part
// of the preparation, and the pieces together within the solve's time.
TEST(ReducedNewtonTest, ReportsItsTimeSplit) {
  const Problem p = MakeProblem("block", {{"n", "40"}});
  const StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load),
                         p.scales};
  ImplicitFb formulation(Reduced());
  const StepResult r = SolveCold(formulation, step);
  ASSERT_EQ(r.status, Status::kConverged) << r.message;
  std::map<std::string, double> s;
  for (const char* key : {"prepare_s", "factorization_s", "forward_sweep_s", "iterations_s",
                          "recovery_s", "backward_sweep_s"}) {
    ASSERT_EQ(r.details.count(key), 1U) << key;
    s[key] = std::stod(r.details.at(key));
    EXPECT_GE(s[key], 0.0) << key;
  }
  EXPECT_LE(s["factorization_s"] + s["forward_sweep_s"], s["prepare_s"]);
  EXPECT_LE(s["backward_sweep_s"], s["recovery_s"]);
  EXPECT_LE(s["prepare_s"] + s["iterations_s"] + s["recovery_s"], r.time_s);
}

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
// The reduced Jacobian's A_cc + T is dense: the condensing solver condenses it even below the
// size from which a sparse system is condensed (no fall-back LU), and solves it to the
// refinement's backward error.
TEST(ReducedNewtonTest, DenseBlockTakesTheCondensedRoute) {
  const Problem p = MakeProblem("block", {{"n", "40"}});
  ColdReducedStep cold(p);
  ReducedStepSystem& reduced = cold.reduced;
  ASSERT_TRUE(reduced.Prepare(cold.start.x));
  ASSERT_LT(reduced.num_contact_dofs(), 1000);
  ASSERT_TRUE(reduced.structure()->dense_stiffness);
  const Vec z = reduced.Reduce(cold.start.x);
  SpMat j;
  reduced.Jacobian(z, &j);
  std::unique_ptr<LinearSolver> solver = MakeLinearSolver("cholmod");
  solver->SetStructure(reduced.structure());
  ASSERT_TRUE(solver->Factorize(j)) << solver->message();
  const Vec b = Vec::LinSpaced(j.rows(), 1.0, 2.0);
  Vec x;
  ASSERT_TRUE(solver->Solve(b, &x)) << solver->message();
  const CondensedSolverStats* stats = CondensedStats(*solver);
  ASSERT_NE(stats, nullptr);
  EXPECT_EQ(stats->condensed_factorizations, 1);
  EXPECT_EQ(stats->fallback_factorizations, 0);
  const Vec residual = b - j * x;
  EXPECT_LE(residual.lpNorm<Eigen::Infinity>(),
            1e-12 * (Mat(j).cwiseAbs().rowwise().sum().maxCoeff() * x.lpNorm<Eigen::Infinity>() +
                     b.lpNorm<Eigen::Infinity>()));
}
#endif

}  // namespace
}  // namespace cb
