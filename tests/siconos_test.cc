// The Siconos formulations (formulations/siconos/): solves judged by the verdict against closed
// forms and against each other (an LCP as given, a linear model after elimination), the warm
// start, the status mapping of Siconos's info codes (a ray is no limit), the counts on P1 under
// a perturbation at the level of rounding, the controls, and the options. The shared
// fixtures are run by tests/formulations_test.cc; the refusals by siconos_lcp_test.cc.
#include "formulations/siconos/siconos.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <random>
#include <string>

#include "formulations/registry.h"
#include "model/complementarity_model.h"
#include "path/path.h"
#include "problems/problem.h"
#include "siconos_test_models.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

using siconos_test::FixedLoadStep;
using siconos_test::ScaledPairs;
using siconos_test::SpringsAgainstWall;

const char* const kNames[] = {"siconos-lemke", "siconos-newton-fb", "siconos-newton-min"};

std::unique_ptr<Formulation> Make(const std::string& name,
                                  std::map<std::string, std::string> options = {}) {
  FormulationConfig config;
  config.options = std::move(options);
  return MakeFormulation(name, config);
}

#define SKIP_WITHOUT_SICONOS() \
  if (!SiconosAvailable()) GTEST_SKIP() << "built without Siconos numerics"

StartPoint Start(const StepProblem& step, StartKind kind) {
  StartPoint start;
  start.kind = kind;
  start.du = Vec::Zero(step.num_dofs());
  start.dlambda = step.constraint.target - step.base.lambda;
  start.r = step.base.r;
  return start;
}

// A strictly monotone LCP of size n (M = A A^T + I, q random): one solution.
ComplementarityModel RandomLcp(int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Mat a(n, n);
  Vec q(n);
  for (int i = 0; i < n; ++i) {
    q[i] = uniform(rng);
    for (int j = 0; j < n; ++j) a(i, j) = uniform(rng);
  }
  return ComplementarityModel::Lcp(Mat(a * a.transpose() + Mat::Identity(n, n)), q);
}

TEST(SiconosTest, AvailableExactlyWhenBuiltWithSiconos) {
#ifdef CONTACTBENCH_HAVE_SICONOS
  EXPECT_TRUE(SiconosAvailable());
#else
  EXPECT_FALSE(SiconosAvailable());
  for (const char* name : kNames) EXPECT_THROW(Make(name), std::invalid_argument) << name;
#endif
}

TEST(SiconosTest, EverySolverMatchesTheClosedFormAfterElimination) {
  SKIP_WITHOUT_SICONOS();
  const SpringsAgainstWall model(2.0, 3.0, 1.0, 0.5);
  for (double lambda : {0.2, 2.0}) {  // free, then in contact
    const StepProblem step = FixedLoadStep(model, lambda, 0.1, 4.0);
    const State answer = model.Answer(lambda);
    for (const char* name : kNames) {
      for (StartKind kind : {StartKind::kWarm, StartKind::kCold}) {
        auto f = Make(name);
        ASSERT_TRUE(f->Accepts(step));
        const StepResult r = f->Solve(step, Start(step, kind));
        EXPECT_EQ(r.status, Status::kConverged) << name << ": " << r.message;
        EXPECT_TRUE(Judge(step, r.point, 1e-10).verified) << name << " lambda " << lambda;
        EXPECT_LE((r.point.du - answer.u).norm(), 1e-10) << name << " lambda " << lambda;
        EXPECT_NEAR(r.point.r[0], answer.r[0], 1e-10) << name << " lambda " << lambda;
        EXPECT_EQ(r.details.at("lcp"), "displacements eliminated (M = G K^-1 G^T)");
      }
    }
  }
}

TEST(SiconosTest, TheThreeSolversAgreeOnALargerLcp) {
  SKIP_WITHOUT_SICONOS();
  const ComplementarityModel model = RandomLcp(40);
  const StepProblem step = FixedLoadStep(model, 0.0, 1.0, 1.0);
  Vec first;
  for (const char* name : kNames) {
    auto f = Make(name);
    const StepResult r = f->Solve(step, Start(step, StartKind::kCold));
    EXPECT_EQ(r.status, Status::kConverged) << name << ": " << r.message;
    EXPECT_TRUE(Judge(step, r.point, 1e-9).verified) << name;
    EXPECT_LT(model.NaturalResidual(r.point.du), 1e-9) << name;
    EXPECT_GT(r.counts.iterations, 0) << name;
    if (first.size() == 0) {
      first = r.point.du;
    } else {
      EXPECT_LE((r.point.du - first).lpNorm<Eigen::Infinity>(), 1e-8) << name;
    }
  }
}

TEST(SiconosTest, P1sCountsDoNotMoveWithTheRoundingOfItsInput) {
  // P1 with its pair rows scaled by 1 + O(1e-14) (ScaledPairs: the same problem, perturbed at
  // the level of the rounding that BLAS threads bring into the reduction). Before the rigid
  // basis was canonical and the split rigid rows relaxed (siconos_lcp.h), such perturbations
  // moved Lemke's pivots and the Newton solvers' iterations and sent some solves onto a ray or
  // a failed line search: every solve must verify with the unperturbed problem's count.
  SKIP_WITHOUT_SICONOS();
  for (const char* n : {"20", "30"}) {
    const Problem block = MakeProblem("block", {{"n", n}});
    const auto step_of = [&block](const ContactModel& model) {
      return StepProblem{&model, ZeroState(model), StepConstraint::FixedLoad(block.load),
                         block.scales};
    };
    for (const char* name : kNames) {
      auto f = Make(name);
      const StepProblem step = step_of(*block.model);
      const StepResult first = f->Solve(step, Start(step, StartKind::kCold));
      ASSERT_EQ(first.status, Status::kConverged) << name << " n = " << n << ": " << first.message;
      EXPECT_TRUE(Judge(step, first.point, 1e-8).verified) << name << " n = " << n;
      for (unsigned seed = 1; seed <= 6; ++seed) {
        const ScaledPairs model(*block.model,
                                ScaledPairs::Factors(block.model->num_pairs(), 1e-14, seed));
        const StepProblem perturbed = step_of(model);
        const StepResult r = f->Solve(perturbed, Start(perturbed, StartKind::kCold));
        EXPECT_EQ(r.status, Status::kConverged) << name << " n = " << n << " seed " << seed;
        EXPECT_TRUE(Judge(perturbed, r.point, 1e-8).verified) << name << " n = " << n;
        EXPECT_EQ(r.counts.iterations, first.counts.iterations)
            << name << " n = " << n << " seed " << seed;
      }
    }
  }
}

TEST(SiconosTest, NewtonWarmStartedAtTheAnswerTakesNoIteration) {
  SKIP_WITHOUT_SICONOS();
  const ComplementarityModel model = RandomLcp(20);
  const StepProblem step = FixedLoadStep(model, 0.0, 1.0, 1.0);
  for (const char* name : {"siconos-newton-fb", "siconos-newton-min"}) {
    auto f = Make(name);
    const StepResult cold = f->Solve(step, Start(step, StartKind::kCold));
    ASSERT_EQ(cold.status, Status::kConverged) << name;
    StartPoint warm = Start(step, StartKind::kWarm);
    warm.du = cold.point.du;  // an LCP as given: z = u^k + du
    const StepResult again = f->Solve(step, warm);
    EXPECT_EQ(again.status, Status::kConverged) << name;
    EXPECT_LT(again.counts.iterations, cold.counts.iterations) << name;
    EXPECT_LE(again.counts.iterations, 1) << name;
  }
}

TEST(SiconosTest, TheIterationLimitIsReportedAsSuch) {
  SKIP_WITHOUT_SICONOS();
  const ComplementarityModel model = RandomLcp(40);
  const StepProblem step = FixedLoadStep(model, 0.0, 1.0, 1.0);
  auto f = Make("siconos-newton-fb", {{"max_iter", "1"}});
  const StepResult r = f->Solve(step, Start(step, StartKind::kCold));
  EXPECT_EQ(r.status, Status::kLimitReached) << r.message;
  EXPECT_EQ(r.details.at("siconos_info"), "1 iteration limit reached");
  EXPECT_FALSE(Judge(step, r.point, 1e-8).verified);
}

TEST(SiconosTest, LemkesRayIsAFailureNotTheLimit) {
  // w = -z - 1 has no z >= 0 with w >= 0: Lemke's path ends on a ray after a pivot or two,
  // which Siconos 4.4 reports with info 1, the code of its pivot limit (10000).
  SKIP_WITHOUT_SICONOS();
  const ComplementarityModel model =
      ComplementarityModel::Lcp(Mat(-Mat::Identity(2, 2)), Vec::Constant(2, -1.0));
  const StepProblem step = FixedLoadStep(model, 0.0, 1.0, 1.0);
  auto f = Make("siconos-lemke");
  const StepResult r = f->Solve(step, Start(step, StartKind::kCold));
  EXPECT_EQ(r.status, Status::kFailed) << r.message;
  EXPECT_LT(r.counts.iterations, 10);
  EXPECT_EQ(r.details.at("siconos_info").rfind("1 ray termination", 0), 0U)
      << r.details.at("siconos_info");
  EXPECT_NE(r.message.find("below the limit of 10000"), std::string::npos) << r.message;
  EXPECT_FALSE(Judge(step, r.point, 1e-8).verified);
}

TEST(SiconosTest, ControlsActBeforeTheCall) {
  SKIP_WITHOUT_SICONOS();
  const ComplementarityModel model = RandomLcp(10);
  const StepProblem step = FixedLoadStep(model, 0.0, 1.0, 1.0);
  auto f = Make("siconos-lemke");
  SolveControls stop;
  stop.interrupted = [] { return true; };
  const StepResult r = f->Solve(step, Start(step, StartKind::kCold), stop);
  EXPECT_EQ(r.status, Status::kStoppedByCaller);
  EXPECT_EQ(r.counts.iterations, 0);
  EXPECT_EQ(r.point.du.size(), step.num_dofs());
}

TEST(SiconosTest, ANanFromTheModelIsAFailedStepWithoutCallingSiconos) {
  SKIP_WITHOUT_SICONOS();
  SpringsAgainstWall model(2.0, 3.0, 1.0, 0.5);
  model.set_nan_force(true);
  const StepProblem step = FixedLoadStep(model, 2.0, 0.1, 4.0);
  for (const char* name : kNames) {
    auto f = Make(name);
    ASSERT_TRUE(f->Accepts(step)) << name;  // K is fine; only the forces are broken
    const StepResult r = f->Solve(step, Start(step, StartKind::kCold));
    EXPECT_EQ(r.status, Status::kFailed) << name;
    EXPECT_NE(r.message.find("non-finite"), std::string::npos) << r.message;
    EXPECT_EQ(r.counts.iterations, 0) << name;
    EXPECT_FALSE(Judge(step, r.point, 1e-8).verified) << name;
  }
}

TEST(SiconosTest, RefusesUnknownAndBadOptions) {
  SKIP_WITHOUT_SICONOS();
  EXPECT_THROW(Make("siconos-lemke", {{"no_such_option", "1"}}), std::invalid_argument);
  EXPECT_THROW(Make("siconos-newton-fb", {{"tol", "0"}}), std::invalid_argument);
  EXPECT_THROW(Make("siconos-newton-min", {{"max_size", "0"}}), std::invalid_argument);
  EXPECT_NO_THROW(Make("siconos-newton-min", {{"max_iter", "50"}, {"max_size", "10"}}));
}

TEST(SiconosTest, SolveRefusesWhatAcceptsRefusesWithTheSameReason) {
  SKIP_WITHOUT_SICONOS();
  const ComplementarityModel model = RandomLcp(10);
  const StepProblem step = FixedLoadStep(model, 0.0, 1.0, 1.0);
  for (int limit : {9, 10}) {
    auto f = Make("siconos-lemke", {{"max_size", std::to_string(limit)}});
    std::string why;
    const bool accepted = f->Accepts(step, &why);
    EXPECT_EQ(accepted, limit >= 10) << limit;
    if (accepted) continue;
    try {
      f->Solve(step, Start(step, StartKind::kCold));
      ADD_FAILURE() << "solved a step that Accepts refuses";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(e.what(), why);
    }
  }
}

}  // namespace
}  // namespace cb
