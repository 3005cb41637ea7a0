// The PETSc backend (formulations/petsc/): closed-form solves by both SNESVI methods, the options
// database as the interface (defaults recorded, the user's options applied over them, a value
// PETSc refuses refused with its message), the status of SNESConvergedReason, the controls, an
// exception thrown in a callback, and the CLI (a short path, --petsc-options). Skipped when this
// build has no PETSc; the MCP itself is checked in every build (petsc_mcp_test.cc), the shared
// fixtures in formulations_test.cc.
#include "formulations/petsc/petsc.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.h"
#include "formulations/registry.h"
#include "path/path.h"
#include "problems/problem.h"
#include "record_table.h"
#include "refusal.h"
#include "run_contactbench.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

class PetscTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!PetscAvailable()) GTEST_SKIP() << "this build has no PETSc";
  }
};

std::unique_ptr<Formulation> Make(const std::string& name, const std::string& petsc_options = "") {
  FormulationConfig config;
  if (!petsc_options.empty()) config.options["petsc_options"] = petsc_options;
  return MakeFormulation(name, config);
}

// The value a PETSc options string ("petsc_options=-key value ...", a settings field) gives
// `key`: the word after its last occurrence, as PETSc's database keeps the last one ("" when the
// key is absent).
std::string PetscOptionValue(const std::string& settings, const std::string& key) {
  std::istringstream words(settings.substr(settings.find('=') + 1));
  std::string value, word, previous;
  while (words >> word) {
    if (previous == key) value = word;
    previous = word;
  }
  return value;
}

StartPoint Cold(const StepProblem& step) {
  StartPoint start;
  start.kind = StartKind::kCold;
  start.du = Vec::Zero(step.num_dofs());
  start.r = Vec::Zero(step.num_pairs());
  return start;
}

// P1 at n = 10: the fixed-load solve whose cold start takes several iterations.
struct Block {
  Problem problem = MakeProblem("block", {{"n", "10"}});
  StepProblem step{problem.model.get(), ZeroState(*problem.model),
                   StepConstraint::FixedLoad(problem.load), problem.scales};
};

// A model that forwards to another and counts the stiffness evaluations: one per evaluation of
// the step equations' Jacobian (StepEquationSystem::Jacobian assembles the stiffness once).
class StiffnessCountingModel final : public ContactModel {
 public:
  explicit StiffnessCountingModel(const ContactModel& inner) : inner_(inner) {}
  int num_dofs() const override { return inner_.num_dofs(); }
  int num_pairs() const override { return inner_.num_pairs(); }
  bool has_energy() const override { return inner_.has_energy(); }
  bool is_linear() const override { return inner_.is_linear(); }
  double Energy(const Vec& u) const override { return inner_.Energy(u); }
  void InternalForce(const Vec& u, Vec* f) const override { inner_.InternalForce(u, f); }
  void Stiffness(const Vec& u, SpMat* k) const override {
    ++evaluations;
    inner_.Stiffness(u, k);
  }
  std::vector<std::pair<int, int>> StiffnessEntries() const override {
    return inner_.StiffnessEntries();
  }
  void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const override {
    ++evaluations;
    inner_.AddStiffness(u, scale, slots, values);
  }
  void Gaps(const Vec& u, Vec* phi) const override { inner_.Gaps(u, phi); }
  void GapJacobian(const Vec& u, SpMat* j) const override { inner_.GapJacobian(u, j); }
  void GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const override {
    inner_.GeneralisedReaction(u, r, reaction);
  }
  void GapCurvature(const Vec& u, const Vec& r, SpMat* c) const override {
    inner_.GapCurvature(u, r, c);
  }
  void GapsAndReaction(const Vec& u, const Vec& r, Vec* phi, Vec* reaction) const override {
    inner_.GapsAndReaction(u, r, phi, reaction);
  }
  void GapDerivatives(const Vec& u, const Vec& r, SpMat* j, SpMat* c) const override {
    inner_.GapDerivatives(u, r, j, c);
  }
  const Vec& load_pattern() const override { return inner_.load_pattern(); }

  mutable int evaluations = 0;

 private:
  const ContactModel& inner_;
};

TEST_P(PetscTest, EvaluatesTheJacobianOnlyWhenPetscAsksForIt) {
  Block b;
  StiffnessCountingModel counting(*b.problem.model);
  StepProblem step = b.step;
  step.model = &counting;
  auto formulation = Make(GetParam());
  // The first solve makes PETSc's operands from the pattern, the second reuses them: neither
  // evaluates a Jacobian PETSc did not ask for. SNESVI asks once per Newton iteration.
  for (int solve = 0; solve < 2; ++solve) {
    counting.evaluations = 0;
    const StepResult r = formulation->Solve(step, Cold(step));
    ASSERT_EQ(r.status, Status::kConverged) << r.message;
    EXPECT_GT(r.counts.iterations, 1);
    EXPECT_EQ(counting.evaluations, r.counts.jacobian_evals) << "solve " << solve;
    EXPECT_EQ(r.counts.jacobian_evals, r.counts.iterations) << "solve " << solve;
  }
}

TEST_P(PetscTest, SolvesTheBarAgainstTheWallToItsClosedForm) {
  const fixtures::Fixture& f = fixtures::FindFixture("bar_wall");
  const StepProblem step = f.Step();
  auto formulation = Make(GetParam());
  const StepResult r = formulation->Solve(step, Cold(step));
  EXPECT_EQ(r.status, Status::kConverged) << r.message;
  EXPECT_TRUE(Judge(step, r.point, 1e-10).verified);
  const State s{step.base.u + r.point.du, r.point.r, step.base.lambda + r.point.dlambda};
  EXPECT_TRUE(f.check(s));
  EXPECT_GT(r.counts.iterations, 0);
  EXPECT_GE(r.counts.residual_evals, r.counts.iterations);
  EXPECT_EQ(r.counts.jacobian_evals, r.counts.iterations);
  EXPECT_EQ(r.counts.linear_solves, r.counts.iterations);  // preonly: one per Newton step
  EXPECT_EQ(r.history.size(), static_cast<std::size_t>(r.counts.iterations) + 1);
  EXPECT_EQ(r.details.at("petsc_reason"), "2 CONVERGED_FNORM_ABS");
}

TEST_P(PetscTest, SolvesAfterMoreInstancesThanPetscsOptionsDatabaseHolds) {
  // A benchmark makes a formulation per repetition; each used to add its options under a new
  // prefix until PETSc's database (512 entries in 3.18) refused the next one.
  const fixtures::Fixture& f = fixtures::FindFixture("bar_wall");
  const StepProblem step = f.Step();
  for (int instance = 0; instance < 600; ++instance) {
    auto formulation = Make(GetParam());
    if (instance % 100 != 99) continue;
    const StepResult r = formulation->Solve(step, Cold(step));
    ASSERT_EQ(r.status, Status::kConverged) << "instance " << instance << ": " << r.message;
  }
}

TEST_P(PetscTest, RecordsItsDefaultsAndAppliesTheUsersOptionsOverThem) {
  auto plain = Make(GetParam());
  const std::string type = GetParam() == "petsc-rsls" ? "vinewtonrsls" : "vinewtonssls";
  EXPECT_EQ(PetscOptionValue(plain->settings(), "-snes_type"), type) << plain->settings();
  const std::string factorisation = GetParam() == "petsc-rsls" ? "umfpack" : "mumps";
  EXPECT_EQ(PetscOptionValue(plain->settings(), "-pc_factor_mat_solver_type"), factorisation)
      << plain->settings();
  // One Newton step cannot solve P1 from the cold start: the iteration limit, as PETSc says.
  Block b;
  auto limited = Make(GetParam(), "-snes_max_it 1");
  EXPECT_EQ(PetscOptionValue(limited->settings(), "-snes_max_it"), "1") << limited->settings();
  const StepResult r = limited->Solve(b.step, Cold(b.step));
  EXPECT_EQ(r.status, Status::kLimitReached) << r.message;
  EXPECT_EQ(r.counts.iterations, 1);
  EXPECT_EQ(r.details.at("petsc_reason"), "-5 DIVERGED_MAX_IT");
  // The message names PETSc's reason ("-5 DIVERGED_MAX_IT": the name after the code).
  const std::string& reason = r.details.at("petsc_reason");
  EXPECT_TRUE(testing_support::Names(r.message, {reason.substr(reason.find(' ') + 1)}));
  // ... and the defaults again for an instance made without them.
  EXPECT_EQ(Make(GetParam())->Solve(b.step, Cold(b.step)).status, Status::kConverged);
}

TEST_P(PetscTest, RefusesWhatPetscRefusesAndUnknownKeys) {
  try {
    Make(GetParam(), "-snes_max_it many");
    FAIL() << "a bad value was accepted";
  } catch (const std::invalid_argument& e) {
    // The option and the value as given.
    EXPECT_TRUE(testing_support::Names(e.what(), {"petsc_options", "-snes_max_it many"}));
  }
  EXPECT_THROW(Make(GetParam(), "-snes_type no_such_method"), std::invalid_argument);
  FormulationConfig config;
  config.options["max_it"] = "3";
  EXPECT_THROW(MakeFormulation(GetParam(), config), std::invalid_argument);
}

TEST_P(PetscTest, HonoursTheInterruptAndTheTimeLimit) {
  Block b;
  auto formulation = Make(GetParam());
  SolveControls stop;
  stop.interrupted = [] { return true; };
  StepResult r = formulation->Solve(b.step, Cold(b.step), stop);
  EXPECT_EQ(r.status, Status::kStoppedByCaller) << r.message;
  EXPECT_EQ(r.counts.iterations, 0);
  SolveControls clock;
  clock.time_limit_s = 1e-12;
  r = formulation->Solve(b.step, Cold(b.step), clock);
  EXPECT_EQ(r.status, Status::kTimeLimit) << r.message;
  EXPECT_NE(r.message.find(TimeLimitMessage(1e-12)), std::string::npos) << r.message;
  // The same instance solves the step afterwards.
  EXPECT_EQ(formulation->Solve(b.step, Cold(b.step)).status, Status::kConverged);
}

TEST_P(PetscTest, AnExceptionInACallbackComesOutOfSolve) {
  Block b;
  auto formulation = Make(GetParam());
  SolveControls throwing;
  throwing.interrupted = []() -> bool { throw std::runtime_error("from the callback"); };
  try {
    formulation->Solve(b.step, Cold(b.step), throwing);
    FAIL() << "the exception was lost";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "from the callback");
  }
  EXPECT_EQ(formulation->Solve(b.step, Cold(b.step)).status, Status::kConverged);
}

INSTANTIATE_TEST_SUITE_P(Formulations, PetscTest, ::testing::Values("petsc-rsls", "petsc-ssls"),
                         [](const auto& info) {
                           return info.param == "petsc-rsls" ? "rsls" : "ssls";
                         });

// --- the CLI ----------------------------------------------------------------------------------

using Outcome = ::cb::testing_support::CliOutcome;

Outcome RunCli(const std::string& arguments) {
  return ::cb::testing_support::RunContactbench(arguments);
}

std::string TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("contactbench_petsc_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

TEST(PetscCliTest, TracesAShortPathAndPassesItsOptionsThrough) {
  if (!PetscAvailable()) GTEST_SKIP() << "this build has no PETSc";
  const std::string dir = TempDir("path");
  Outcome o = RunCli("run --problem two-bar-obstacle --formulation petsc-rsls --steps 8 --out " +
                     dir + " --petsc-options \"-snes_max_it 50\"");
  EXPECT_EQ(o.status, 0) << o.output;
  const auto steps = testing_support::Table(dir + "/steps.csv");
  ASSERT_FALSE(steps.empty());
  EXPECT_EQ(PetscOptionValue(steps[0].at("settings"), "-snes_max_it"), "50");
  // A value PETSc refuses: status 2, with PETSc's reason.
  o = RunCli("run --problem two-bar-obstacle --formulation petsc-ssls --out " + TempDir("bad") +
             " --petsc-options \"-snes_max_it many\"");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_TRUE(testing_support::RefusedOption(
      o.output, testing_support::At("petsc_options", {"-snes_max_it many"})));
  // PETSc options for a formulation that has none.
  o = RunCli("run --problem two-bar-obstacle --formulation implicit-fb --out " + TempDir("other") +
             " --petsc-options \"-snes_max_it 5\"");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_TRUE(testing_support::RefusedOption(
      o.output, testing_support::At("--petsc-options", {"implicit-fb"})));
  // -snes_max_it 1 makes P1's cold solve fail, as PETSc reports it.
  const std::string p1 = TempDir("p1");
  o = RunCli("run --problem block --set n=4 --start cold --formulation petsc-rsls --out " + p1 +
             " --petsc-options \"-snes_max_it 1\"");
  EXPECT_EQ(o.status, 3) << o.output;
  const auto p1_steps = testing_support::Table(p1 + "/steps.csv");
  ASSERT_EQ(p1_steps.size(), 1u);
  EXPECT_EQ(p1_steps[0].at("status"), "limit_reached");
  EXPECT_EQ(p1_steps[0].at("iterations"), "1");
  EXPECT_TRUE(testing_support::Names(p1_steps[0].at("message"), {"DIVERGED_MAX_IT"}));
}

}  // namespace
}  // namespace cb
