// The nonsmooth formulations (nonsmooth-fb, active-set): generalised-Jacobian elements against
// finite differences away from the kinks and against the limiting Jacobians at them, the Armijo
// slope of the FB merit, the restart at a path's turning kink, the iteration limit, and the
// first 50 arc-length steps of P3. The shared fixtures run in tests/formulations_test.cc.
#include "formulations/nonsmooth/nonsmooth.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "fd_check.h"
#include "fixtures.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "formulations/registry.h"
#include "path/arc_length_norm.h"
#include "path/path.h"
#include "path/path_recorder.h"
#include "path/step_solve.h"
#include "problems/problem.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

// --- the complementarity functions and their elements ------------------------------------------

TEST(NonsmoothTest, FischerBurmeisterElementIsTheGradientAwayFromTheOrigin) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-2.0, 2.0);
  for (int i = 0; i < 50; ++i) {
    const double a = unit(rng), b = unit(rng);
    double da = 0, db = 0, drho = 0;
    FischerBurmeisterElement(a, b, 0.0, &da, &db, &drho);
    const double h = 1e-7;
    EXPECT_NEAR(
        da,
        (SmoothedFischerBurmeister(a + h, b, 0) - SmoothedFischerBurmeister(a - h, b, 0)) / (2 * h),
        1e-7);
    EXPECT_NEAR(
        db,
        (SmoothedFischerBurmeister(a, b + h, 0) - SmoothedFischerBurmeister(a, b - h, 0)) / (2 * h),
        1e-7);
  }
}

TEST(NonsmoothTest, FischerBurmeisterElementAtTheOriginIsTheDocumentedLimit) {
  double da = 0, db = 0, drho = 0;
  FischerBurmeisterElement(0.0, 0.0, 0.0, &da, &db, &drho);
  // The limit of the gradient along (a, b) = t (1, 1), t -> 0+ (a B-subdifferential element).
  double la = 0, lb = 0, lr = 0;
  FischerBurmeisterElement(1e-150, 1e-150, 0.0, &la, &lb, &lr);
  EXPECT_NEAR(da, la, 1e-15);
  EXPECT_NEAR(db, lb, 1e-15);
  EXPECT_NEAR(da, M_SQRT1_2 - 1.0, 1e-15);
  // In the Clarke Jacobian {(xi - 1, eta - 1) : xi^2 + eta^2 <= 1}, on its boundary (the limiting
  // gradients), and not the element of another direction, e.g. (0, -1) from (a, b) = (t, 0).
  EXPECT_NEAR((da + 1) * (da + 1) + (db + 1) * (db + 1), 1.0, 1e-15);
  FischerBurmeisterElement(1e-150, 0.0, 0.0, &la, &lb, &lr);
  EXPECT_NE(la, da);
}

TEST(NonsmoothTest, MinElementIsTheGradientAwayFromTiesAndTheActiveLimitAtThem) {
  double da = 0, db = 0;
  MinElement(0.3, 0.7, &da, &db);
  EXPECT_EQ(da, 1.0);
  EXPECT_EQ(db, 0.0);
  MinElement(0.7, 0.3, &da, &db);
  EXPECT_EQ(da, 0.0);
  EXPECT_EQ(db, 1.0);
  // At a tie: the limit from a < b, (1, 0), one of the two limiting Jacobians whose convex
  // hull {(s, 1 - s)} is the Clarke Jacobian (documented: ties go to the active set).
  MinElement(-1.0, -1.0, &da, &db);
  EXPECT_EQ(da, 1.0);
  EXPECT_EQ(db, 0.0);
  EXPECT_EQ(MinFunction(-1.0, 2.0), -1.0);
  EXPECT_EQ(MinFunction(2.0, -1.0), -1.0);
}

// --- the system's Jacobian
// ------------------------------------------------------------------------

struct JacobianCase {
  ComplementarityFunction function;
  ConstraintKind kind;
};

// Readable parameters in GoogleTest's messages.
void PrintTo(const JacobianCase& c, std::ostream* out) {
  *out << (c.function == ComplementarityFunction::kMin ? "min" : "fb") << ", " << ToString(c.kind);
}

class NonsmoothJacobianTest : public ::testing::TestWithParam<JacobianCase> {};

StepProblem RandomStep(const Problem& p, ConstraintKind kind, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int d = p.model->num_dofs();
  const int nc = p.model->num_pairs();
  State base = ZeroState(*p.model);
  for (int i = 0; i < d; ++i) base.u[i] = 0.05 * unit(*rng);
  for (int q = 0; q < nc; ++q) base.r[q] = -std::abs(unit(*rng));
  base.lambda = 3.0;
  return {p.model.get(), base, fixtures::ConstraintOf(kind, *p.model), {0.1, 2.0}};
}

TEST_P(NonsmoothJacobianTest, MatchesFiniteDifferencesAwayFromKinks) {
  const JacobianCase c = GetParam();
  const Problem p = MakeProblem("arch-curved", {{"upper_nodes", "6"}});
  std::mt19937 rng(17);
  const StepProblem step = RandomStep(p, c.kind, &rng);
  NonsmoothSystem system(step, c.function);
  const StepEquationLayout& l = system.layout();
  ASSERT_EQ(system.size(), l.d + 2 * l.nc + 1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Vec x(l.size());
  for (int i = 0; i < l.size(); ++i) x[i] = unit(rng);
  x.segment(0, l.d) *= 0.05;
  auto residual = [&](const Vec& y) {
    Vec f;
    system.Residual(y, &f);
    return f;
  };
  for (int round = 0; round < 2; ++round) {  // the second reuses the cached pattern
    SpMat jac;
    system.Jacobian(x, &jac);
    EXPECT_DERIVATIVE_NEAR(Mat(jac), fd_check::FiniteDifferenceJacobian(residual, x), 1e-6);
    x.segment(0, l.d) *= -0.5;
  }
  EXPECT_EQ(system.nonsmooth_elements(), 0);
}

std::vector<JacobianCase> AllJacobianCases() {
  std::vector<JacobianCase> cases;
  for (auto fn : {ComplementarityFunction::kFischerBurmeister, ComplementarityFunction::kMin}) {
    for (ConstraintKind k : fixtures::kAllConstraintKinds) {
      cases.push_back({fn, k});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(FunctionAndConstraint, NonsmoothJacobianTest,
                         ::testing::ValuesIn(AllJacobianCases()),
                         [](const ::testing::TestParamInfo<JacobianCase>& info) {
                           std::string kind = ToString(info.param.kind);
                           for (char& ch : kind) {
                             if (ch == '-') ch = '_';
                           }
                           return std::string(info.param.function == ComplementarityFunction::kMin
                                                  ? "min_"
                                                  : "fb_") +
                                  kind;
                         });

TEST(NonsmoothTest, AtADegeneratePairTheJacobianUsesTheDocumentedElement) {
  const Problem p = MakeProblem("arch-curved", {{"upper_nodes", "6"}});
  std::mt19937 rng(5);
  const StepProblem step = RandomStep(p, ConstraintKind::kFixedLoad, &rng);
  for (auto fn : {ComplementarityFunction::kFischerBurmeister, ComplementarityFunction::kMin}) {
    NonsmoothSystem system(step, fn);
    const StepEquationLayout& l = system.layout();
    Vec x = Vec::Constant(l.size(), 0.01);
    x[l.g()] = 0.0;  // pair 0 at a = b = 0
    x[l.r()] = 0.0;
    SpMat jac;
    system.Jacobian(x, &jac);
    const Mat j(jac);
    const int row = l.complementarity_row();
    if (fn == ComplementarityFunction::kFischerBurmeister) {
      EXPECT_DOUBLE_EQ(j(row, l.g()), M_SQRT1_2 - 1.0);
      EXPECT_DOUBLE_EQ(j(row, l.r()), -(M_SQRT1_2 - 1.0));  // d/dr^ = -d/db
    } else {
      EXPECT_DOUBLE_EQ(j(row, l.g()), 1.0);  // active: g^ = 0
      EXPECT_DOUBLE_EQ(j(row, l.r()), 0.0);
    }
    EXPECT_EQ(system.nonsmooth_elements(), 1);
  }
}

TEST(NonsmoothTest, FischerBurmeisterMeritHasTheNewtonSlopeEvenAtADegeneratePair) {
  // m = 1/2 ||F||^2 is C^1 with grad m = H^T F for every H in the generalised Jacobian, so along
  // dx = -H^{-1} F its slope is -||F||^2 (what the line search's Armijo test assumes).
  const Problem p = MakeProblem("arch-curved", {{"upper_nodes", "6"}});
  std::mt19937 rng(9);
  const StepProblem step = RandomStep(p, ConstraintKind::kArcLength, &rng);
  NonsmoothSystem system(step, ComplementarityFunction::kFischerBurmeister);
  const StepEquationLayout& l = system.layout();
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Vec x(l.size());
  for (int i = 0; i < l.size(); ++i) x[i] = unit(rng);
  x.segment(0, l.d) *= 0.05;
  x[l.g() + 1] = 0.0;  // a degenerate pair
  x[l.r() + 1] = 0.0;
  Vec f;
  ASSERT_TRUE(system.Residual(x, &f));
  SpMat jac;
  system.Jacobian(x, &jac);
  const Vec dx = -Mat(jac).fullPivLu().solve(f);
  auto merit = [&](double t) {
    Vec ft;
    system.Residual(x + t * dx, &ft);
    return 0.5 * ft.squaredNorm();
  };
  const double h = 1e-7;
  const double slope = (merit(h) - merit(-h)) / (2 * h);
  EXPECT_NEAR(slope, -f.squaredNorm(), 1e-5 * f.squaredNorm());
}

// --- solves -----------------------------------------------------------------------------------

TEST(NonsmoothTest, FactoriesNameTheFormulationsAndRefuseUnknownOptions) {
  FormulationConfig config;
  EXPECT_EQ(MakeNonsmoothFb(config)->name(), "nonsmooth-fb");
  EXPECT_EQ(MakeActiveSet(config)->name(), "active-set");
  EXPECT_EQ(MakeActiveSet(config)->settings(),
            "solver=newton;function=min;linear_solver=" + config.solver_options.linear_solver);
  config.options["rho_min"] = "0.1";
  EXPECT_THROW(MakeNonsmoothFb(config), std::invalid_argument);
  FormulationConfig bad;
  bad.solver = "no-such-solver";
  EXPECT_THROW(MakeActiveSet(bad), std::invalid_argument);
}

TEST(NonsmoothTest, ActiveSetStopsAtTheIterationLimit) {
  const Problem p = MakeProblem("block", {{"n", "10"}});
  NonsmoothOptions o;
  o.function = ComplementarityFunction::kMin;
  o.solver_options.max_iterations = 1;
  NonsmoothFormulation f(o);
  StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(1.0), p.scales};
  StartPoint cold;
  cold.kind = StartKind::kCold;
  const StepResult r = f.Solve(step, cold);
  EXPECT_EQ(r.status, Status::kLimitReached) << r.message;
  EXPECT_EQ(r.counts.iterations, 1);
  EXPECT_EQ(r.details.at("restarted"), "0");  // fixed load: no restart
  // With the default limit it converges, and the records say how the active set moved.
  NonsmoothFormulation g(NonsmoothOptions{ComplementarityFunction::kMin, "newton", {}, true});
  const StepResult s = g.Solve(step, cold);
  EXPECT_EQ(s.status, Status::kConverged) << s.message;
  EXPECT_TRUE(Judge(step, s.point, 1e-8).verified);
  EXPECT_GT(std::stoi(s.details.at("active_set_changes")), 0);
  EXPECT_EQ(static_cast<int>(s.history.size()), s.counts.iterations);
}

TEST(NonsmoothTest, ActiveSetReportsRevisitedActiveSetsWhenItFails) {
  // The Kojima-Shindo NCP from the cold start g^0 = -1, r^0 = +1 (left out of the shared
  // fixtures for this reason): the iteration stalls, and the active sets it went through are
  // reported, with the revisits, instead of looping.
  const fixtures::Fixture& f = fixtures::FindFixture("kojima_shindo");
  NonsmoothOptions o;
  o.function = ComplementarityFunction::kMin;
  NonsmoothFormulation formulation(o);
  StartPoint cold;
  cold.kind = StartKind::kCold;
  const StepResult r = formulation.Solve(f.Step(), cold);
  ASSERT_NE(r.status, Status::kConverged);
  EXPECT_LE(r.counts.iterations, o.solver_options.max_iterations);
  const int revisits = std::stoi(r.details.at("active_set_revisits"));
  EXPECT_GT(revisits, 0);
  EXPECT_GE(std::stoi(r.details.at("active_set_changes")), revisits);
  EXPECT_NE(r.message.find("cycling"), std::string::npos) << r.message;
}

// Keeps the accepted attempts and the kinks.
class Collector final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& a) override {
    ++attempts;
    if (a.accepted) accepted.push_back(a);
  }
  void OnKink(const KinkRecord& k) override { kinks.push_back(k); }
  int attempts = 0;
  std::vector<StepAttempt> accepted;
  std::vector<KinkRecord> kinks;
};

// The step of the two-bar truss's path within which the apex meets the floor (the load turns
// there), posed with the straight prediction, the previous increment rescaled: it points into
// the floor. (The path driver bends such a prediction at the contact change,
// corner_prediction.h; the restart is the formulation's own rescue for a start that does not.)
TEST(NonsmoothTest, RestartTurnsAStepOntoTheFloorWhereItsPredictionPointsIntoIt) {
  const fixtures::Fixture& fixture = fixtures::FindFixture("two_bar_obstacle_path");
  const Problem& p = fixture.problem;
  PathOptions po;
  po.arc_length = fixture.theta;
  po.max_steps = fixture.steps;
  PathRecorder path;
  NonsmoothFormulation tracer{NonsmoothOptions{}};
  ASSERT_EQ(TraceArcLengthPath(*p.model, p.scales, fixture.base, tracer, po, &path).status,
            Status::kConverged);
  ASSERT_EQ(path.kinks.size(), 1u);
  const int k = path.kinks[0].step;
  ASSERT_GE(k, 3);
  const State& base = path.steps[k - 2].state;
  const State& before = path.steps[k - 3].state;
  const double w = po.lambda_weight;
  const double scale = fixture.theta / HNorm(base.u - before.u, base.lambda - before.lambda, w);
  const StepProblem step{p.model.get(), base, StepConstraint::ArcLength(fixture.theta, w),
                         p.scales};
  StartPoint straight;
  straight.du = (base.u - before.u) * scale;
  straight.dlambda = (base.lambda - before.lambda) * scale;
  straight.r = base.r;
  for (auto fn : {ComplementarityFunction::kFischerBurmeister, ComplementarityFunction::kMin}) {
    for (bool restart : {true, false}) {
      NonsmoothOptions o;
      o.function = fn;
      o.restart = restart;
      NonsmoothFormulation f(o);
      const JudgedStep judged = SolveAndJudge(f, step, straight, po);
      const StepResult& r = judged.result;
      const State& reached = judged.state;
      if (restart) {
        EXPECT_TRUE(SolvedAndVerified(r, judged.verdict)) << f.name() << ": " << r.message;
        EXPECT_EQ(r.details.at("restarted"), "1") << f.name();
        EXPECT_TRUE(fixture.CheckSolution(reached)) << f.name();
        EXPECT_GT(reached.u.dot(straight.du), base.u.dot(straight.du)) << f.name();
      } else {
        // Without it the solve ends short of the path (the path driver then cuts back).
        EXPECT_FALSE(SolvedAndVerified(r, judged.verdict)) << f.name();
        EXPECT_EQ(r.details.at("restarted"), "0") << f.name();
      }
    }
  }
}

}  // namespace

// ArchCurvedTest's parameter readable in GoogleTest's messages: found by argument-dependent
// lookup, so in the enum's namespace cb.
void PrintTo(ComplementarityFunction function, std::ostream* out) {
  *out << (function == ComplementarityFunction::kMin ? "min" : "fb");
}

namespace {

// P3: the first 50 arc-length steps at the report's theta, every step and kink verified, with
// the counts filled.
class ArchCurvedTest : public ::testing::TestWithParam<ComplementarityFunction> {};

TEST_P(ArchCurvedTest, First50StepsAllVerified) {
  const Problem p = MakeProblem("arch-curved");
  NonsmoothOptions o;
  o.function = GetParam();
  NonsmoothFormulation f(o);
  PathOptions po;
  po.arc_length = p.arc_length;
  po.max_steps = 50;
  po.max_cutbacks = 0;  // every step must verify at the report's theta
  Collector c;
  const PathSummary s = TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), f, po, &c);
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  ASSERT_EQ(c.accepted.size(), 50u);
  SolveCounts total;
  for (const StepAttempt& a : c.accepted) {
    EXPECT_TRUE(a.verdict.verified) << "step " << a.step;
    const SolveCounts& n = a.result.counts;
    EXPECT_GE(n.residual_evals, n.iterations + 1) << "step " << a.step;
    EXPECT_GE(n.jacobian_evals, 1) << "step " << a.step;
    EXPECT_GE(n.linear_solves, 1) << "step " << a.step;
    EXPECT_EQ(static_cast<int>(a.result.history.size()), n.iterations) << "step " << a.step;
    total.iterations += n.iterations;
    total.residual_evals += n.residual_evals;
    total.jacobian_evals += n.jacobian_evals;
    total.linear_solves += n.linear_solves;
  }
  for (const KinkRecord& k : c.kinks) {
    EXPECT_TRUE(k.verdict.verified) << "kink of pair " << k.pair << " at step " << k.step;
  }
  // The same steps with implicit-fb, for the record.
  ImplicitFb reference;
  Collector rc;
  const PathSummary rs =
      TraceArcLengthPath(*p.model, p.scales, ZeroState(*p.model), reference, po, &rc);
  ASSERT_EQ(rs.status, Status::kConverged) << rs.message;
  int reference_iterations = 0;
  for (const StepAttempt& a : rc.accepted) reference_iterations += a.result.counts.iterations;
  // Same path: the final states agree.
  EXPECT_TRUE(
      fixtures::RelativelyClose(s.final_state.u, rs.final_state.u, 1e-6, p.scales.length, "u"));
  EXPECT_NEAR(s.final_state.lambda, rs.final_state.lambda, 1e-6 * std::abs(rs.final_state.lambda));
  RecordProperty("iterations", total.iterations);
  RecordProperty("implicit_fb_iterations", reference_iterations);
  std::cout << "[ counts   ] " << f.name() << " P3 50 steps: iterations " << total.iterations
            << ", residual evals " << total.residual_evals << ", Jacobian evals "
            << total.jacobian_evals << ", linear solves " << total.linear_solves << ", kinks "
            << c.kinks.size() << "; implicit-fb iterations " << reference_iterations << "\n";
}

INSTANTIATE_TEST_SUITE_P(Nonsmooth, ArchCurvedTest,
                         ::testing::Values(ComplementarityFunction::kFischerBurmeister,
                                           ComplementarityFunction::kMin),
                         [](const ::testing::TestParamInfo<ComplementarityFunction>& info) {
                           return std::string(info.param == ComplementarityFunction::kMin
                                                  ? "active_set"
                                                  : "nonsmooth_fb");
                         });

}  // namespace
}  // namespace cb

namespace cb {
namespace {

// The shared step fixtures with the other equation solvers (the semismooth Newton method is the
// default; formulations_test.cc runs it on every fixture).
struct SolverCase {
  ComplementarityFunction function;
  std::string solver;
  std::string fixture;
};

void PrintTo(const SolverCase& c, std::ostream* out) {
  *out << (c.function == ComplementarityFunction::kMin ? "active-set" : "nonsmooth-fb") << ", "
       << c.solver << ", " << c.fixture;
}

class NonsmoothSolverFixtureTest : public ::testing::TestWithParam<SolverCase> {};

TEST_P(NonsmoothSolverFixtureTest, WarmStepIsVerifiedAndKnown) {
  const SolverCase c = GetParam();
  const fixtures::Fixture& f = fixtures::FindFixture(c.fixture);
  NonsmoothOptions o;
  o.function = c.function;
  o.solver = c.solver;
  NonsmoothFormulation formulation(o);
  const StepProblem step = f.Step();
  StartPoint start;
  start.du = Vec::Zero(f.problem.model->num_dofs());
  start.dlambda = f.constraint.target - f.base.lambda;
  start.r = f.base.r;
  const StepResult r = formulation.Solve(step, start);
  const Verdict v = Judge(step, r.point, 1e-8);
  EXPECT_TRUE(v.verified) << r.message << ": eq " << v.eq_res << " comp " << v.comp_res;
  EXPECT_TRUE(f.CheckSolution({f.base.u + r.point.du, r.point.r, f.base.lambda + r.point.dlambda}));
  EXPECT_GT(r.counts.residual_evals, 0);
}

std::vector<SolverCase> AllSolverCases() {
  std::vector<SolverCase> cases;
  for (auto fn : {ComplementarityFunction::kFischerBurmeister, ComplementarityFunction::kMin}) {
    for (const char* solver : {"dogleg", "quasi-newton"}) {
      for (const fixtures::Fixture& f : fixtures::Fixtures()) {
        if (!f.path) cases.push_back({fn, solver, f.name});
      }
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(FunctionSolverFixture, NonsmoothSolverFixtureTest,
                         ::testing::ValuesIn(AllSolverCases()),
                         [](const ::testing::TestParamInfo<SolverCase>& info) {
                           std::string name =
                               std::string(info.param.function == ComplementarityFunction::kMin
                                               ? "active_set_"
                                               : "nonsmooth_fb_") +
                               info.param.solver + "_" + info.param.fixture;
                           for (char& ch : name) {
                             if (ch == '-') ch = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace cb
