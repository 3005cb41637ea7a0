// The warm-state rule (src/step/warm_state.md): a step's answer depends only on its StepProblem
// and StartPoint, not on the steps a formulation solved before, because what a step takes from
// the previous one travels through the StartPoint and the members hold only caches. Checked for
// every formulation of the rule (PETSc's and Siconos's aside) with the LU that factorises afresh
// ("sparse-lu"; KLU's reuse of an earlier pivot order is the rule's documented exception), and
// the one time-limit check of the backends (src/step/time_limit.h).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "fixture_start.h"
#include "fixtures.h"
#include "formulations/registry.h"
#include "step/time_limit.h"

namespace cb {
namespace {

using fixtures::FindFixture;
using fixtures::Fixture;
using fixtures::StartFor;

bool UnderTheRule(const FormulationInfo& info) {
  return info.available && info.name.rfind("petsc", 0) != 0 && info.name.rfind("siconos", 0) != 0;
}

std::unique_ptr<Formulation> Make(const std::string& name) {
  FormulationConfig config;
  config.solver_options.linear_solver = "sparse-lu";
  return MakeFormulation(name, config);
}

// Everything a solve returns that an earlier solve could move: the point, the status, the
// counts and the history.
void ExpectSameAnswer(const StepResult& a, const StepResult& b, const std::string& what) {
  EXPECT_EQ(a.status, b.status) << what;
  EXPECT_EQ(a.message, b.message) << what;
  EXPECT_EQ(a.point.du, b.point.du) << what;
  EXPECT_EQ(a.point.dlambda, b.point.dlambda) << what;
  EXPECT_EQ(a.point.g, b.point.g) << what;
  EXPECT_EQ(a.point.r, b.point.r) << what;
  EXPECT_EQ(a.counts.iterations, b.counts.iterations) << what;
  EXPECT_EQ(a.counts.residual_evals, b.counts.residual_evals) << what;
  ASSERT_EQ(a.history.size(), b.history.size()) << what;
  for (std::size_t i = 0; i < a.history.size(); ++i) {
    EXPECT_EQ(a.history[i].merit, b.history[i].merit) << what << ", iteration " << i + 1;
  }
}

TEST(WarmStateRuleTest, AStepsAnswerDoesNotDependOnTheStepsSolvedBefore) {
  const Fixture& first = FindFixture("two_bar_obstacle_step");
  const Fixture& other = FindFixture("bar_wall");
  const StepProblem step = first.Step();
  const StepProblem other_step = other.Step();
  int checked = 0;
  for (const FormulationInfo& info : FormulationRegistry()) {
    if (!UnderTheRule(info)) continue;
    auto fresh = Make(info.name);
    if (!fresh->Accepts(step) || !fresh->Accepts(other_step)) continue;
    for (StartKind kind : {StartKind::kWarm, StartKind::kCold}) {
      const std::string what = info.name + " (" + ToString(kind) + ")";
      const StartPoint start = StartFor(first, kind);
      const StepResult alone = Make(info.name)->Solve(step, start);
      // The same formulation object after other steps: the other model, the other start kind,
      // and this step itself.
      auto used = Make(info.name);
      used->Solve(other_step, StartFor(other, StartKind::kWarm));
      used->Solve(step,
                  StartFor(first, kind == StartKind::kWarm ? StartKind::kCold : StartKind::kWarm));
      const StepResult again = used->Solve(step, start);
      ExpectSameAnswer(alone, again, what);
      ++checked;
    }
  }
  // implicit-fb, nonsmooth-fb and active-set are in every build.
  EXPECT_GE(checked, 2 * 3);
}

TEST(WarmStateRuleTest, TheTimeLimitIsPastOnlyWhenSetAndExceeded) {
  const Stopwatch clock;
  SolveControls controls;
  EXPECT_FALSE(PastTimeLimit(controls, clock));  // 0: no limit
  controls.time_limit_s = 1e-12;
  while (clock.Seconds() <= 1e-12) {
  }
  EXPECT_TRUE(PastTimeLimit(controls, clock));
  controls.time_limit_s = 3600.0;
  EXPECT_FALSE(PastTimeLimit(controls, clock));
}

}  // namespace
}  // namespace cb
