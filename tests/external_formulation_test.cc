// The step as data for a method written outside the suite (formulations/external/): its rows
// vanish at implicit-fb's verified answer of every one-step fixture, its Jacobian is the
// derivative of its rows, and the formulation around a callable passes on the method's point
// and counts, turns a throwing method or a point of the wrong size into a failed step, and the
// registry refuses a name already taken.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "fd_check.h"
#include "fixture_start.h"
#include "fixtures.h"
#include "formulations/external/callback_formulation.h"
#include "formulations/registry.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

using fixtures::Fixture;

// implicit-fb's answer to a fixture's step in the unknowns of the step system.
Vec ReferenceAnswer(const Fixture& f, ExternalStepSystem& system) {
  auto reference = MakeFormulation("implicit-fb", FormulationConfig());
  const StepResult r = reference->Solve(system.step(), fixtures::StartFor(f, StartKind::kWarm));
  EXPECT_TRUE(Judge(system.step(), r.point, 1e-8).verified) << f.name;
  return system.FromPoint(r.point);
}

TEST(ExternalStepSystemTest, RowsVanishAtTheVerifiedAnswerOfEveryOneStepFixture) {
  for (const Fixture& f : fixtures::Fixtures()) {
    if (f.path) continue;
    const StepProblem step = f.Step();
    ExternalStepSystem system(step);
    const Vec x = ReferenceAnswer(f, system);
    Vec rows;
    ASSERT_TRUE(system.Residual(x, &rows));
    EXPECT_EQ(system.rows() + static_cast<int>(system.pair_gaps().size()), system.size());
    EXPECT_LT(rows.cwiseAbs().maxCoeff(), 1e-6) << f.name;
    for (std::size_t i = 0; i < system.pair_gaps().size(); ++i) {
      const double a = x[system.pair_gaps()[i]], b = -x[system.pair_reactions()[i]];
      EXPECT_LT(std::abs(std::min(a, b)), 1e-8) << f.name << " pair " << i;
    }
    const StepPoint back = system.ToPoint(x);
    EXPECT_LT((system.FromPoint(back) - x).cwiseAbs().maxCoeff(), 1e-14) << f.name;
  }
}

TEST(ExternalStepSystemTest, JacobianIsTheDerivativeOfTheRows) {
  for (const Fixture& f : fixtures::Fixtures()) {
    if (f.path) continue;
    const StepProblem step = f.Step();
    ExternalStepSystem system(step);
    const Vec x = system.Start(fixtures::StartFor(f, StartKind::kWarm)) +
                  0.01 * Vec::LinSpaced(system.size(), -1.0, 1.0);  // off the start's kinks
    auto rows = [&](const Vec& at) {
      Vec out;
      system.Residual(at, &out);
      return out;
    };
    SCOPED_TRACE(f.name);
    EXPECT_DERIVATIVE_NEAR(Mat(system.Jacobian(x)), fd_check::FiniteDifferenceJacobian(rows, x),
                           1e-5);
  }
}

const Fixture& FirstOneStepFixture() {
  for (const Fixture& f : fixtures::Fixtures()) {
    if (!f.path) return f;
  }
  throw std::logic_error("no one-step fixture");
}

StepResult SolveWith(const ExternalMethod& method) {
  const Fixture& f = FirstOneStepFixture();
  CallbackFormulation formulation("test-method", "external", method, {});
  return formulation.Solve(f.Step(), fixtures::StartFor(f, StartKind::kWarm));
}

TEST(CallbackFormulationTest, PassesOnTheMethodsPointAndCounts) {
  const Fixture& f = FirstOneStepFixture();
  const StepResult r = SolveWith([&f](ExternalStepSystem& system, const ExternalCall&) {
    return ExternalAnswer{ReferenceAnswer(f, system), Status::kConverged, "done", {4, 5, 6, 7}, {}};
  });
  EXPECT_EQ(r.status, Status::kConverged);
  EXPECT_EQ(r.message, "done");
  EXPECT_EQ(r.counts.iterations, 4);
  EXPECT_EQ(r.counts.linear_solves, 7);
  EXPECT_TRUE(Judge(f.Step(), r.point, 1e-8).verified);
}

TEST(CallbackFormulationTest, AThrowingMethodOrAWrongSizeIsAFailedStep) {
  const StepResult thrown =
      SolveWith([](ExternalStepSystem&, const ExternalCall&) -> ExternalAnswer {
        throw std::runtime_error("my bug");
      });
  EXPECT_EQ(thrown.status, Status::kFailed);
  EXPECT_NE(thrown.message.find("my bug"), std::string::npos);
  const StepResult short_point = SolveWith([](ExternalStepSystem& system, const ExternalCall&) {
    return ExternalAnswer{Vec::Zero(system.size() - 1), Status::kConverged, "", {}, {}};
  });
  EXPECT_EQ(short_point.status, Status::kFailed);
  EXPECT_NE(short_point.message.find("unknowns, not"), std::string::npos);
}

TEST(RegisterFormulationTest, RefusesATakenNameABadNameAndNoFactory) {
  const auto method = [](ExternalStepSystem&, const ExternalCall& call) {
    return ExternalAnswer{call.x0, Status::kConverged, "", {}, {}};
  };
  EXPECT_THROW(RegisterFormulation(ExternalFormulationInfo("implicit-fb", "", "", method)),
               std::invalid_argument);
  EXPECT_THROW(RegisterFormulation(ExternalFormulationInfo("bad name", "", "", method)),
               std::invalid_argument);
  EXPECT_THROW(RegisterFormulation({"no-factory", "", true, nullptr}), std::invalid_argument);
  EXPECT_EQ(FormulationNames().size(), FormulationRegistry().size());
  for (const auto& name : FormulationNames()) EXPECT_NE(name, "no-factory");
}

// What a formulation can take is its registry entry's word, not its name's: the lookups agree
// with the entries, an unknown name takes nothing, a distributed formulation is a PETSc one (the
// distributed backend runs PETSc's SNES), and one registered at run time is neither unless its
// entry says so.
TEST(RegisterFormulationTest, CapabilitiesAreTheEntrys) {
  for (const FormulationInfo& info : FormulationRegistry()) {
    ASSERT_EQ(FindFormulation(info.name), &info) << info.name;
    EXPECT_EQ(TakesPetscOptions(info.name), info.takes_petsc_options) << info.name;
    if (info.distributed) {
      EXPECT_TRUE(info.takes_petsc_options) << info.name;
    }
  }
  EXPECT_EQ(FindFormulation("no-such-formulation"), nullptr);
  EXPECT_FALSE(TakesPetscOptions("no-such-formulation"));
  const auto method = [](ExternalStepSystem&, const ExternalCall& call) {
    return ExternalAnswer{call.x0, Status::kConverged, "", {}, {}};
  };
  const FormulationInfo external = ExternalFormulationInfo("dist-petsc-lookalike", "", "", method);
  EXPECT_FALSE(external.distributed);
  EXPECT_FALSE(external.takes_petsc_options);
}

}  // namespace
}  // namespace cb
