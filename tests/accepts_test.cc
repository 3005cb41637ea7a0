// Formulation::Accepts, the capability query: every refusal of the registry's formulations
// with its reason (constraint kind, model without energy, dense-size limits), the sizes at the
// edge of each limit, and Solve refusing the same steps with the same reason. Formulations not
// built into this binary are skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "fixtures.h"
#include "formulations/registry.h"
#include "path/path.h"
#include "problems/problem.h"

namespace cb {
namespace {

constexpr const auto& kAllKinds = fixtures::kAllConstraintKinds;

bool Built(const std::string& name) {
  for (const FormulationInfo& info : FormulationRegistry()) {
    if (info.name == name) return info.available;
  }
  return false;
}

#define SKIP_UNLESS_BUILT(name) \
  if (!Built(name)) GTEST_SKIP() << name << " is not built into this binary"

std::unique_ptr<Formulation> Make(const std::string& name,
                                  std::map<std::string, std::string> options = {}) {
  FormulationConfig config;
  config.options = std::move(options);
  return MakeFormulation(name, config);
}

StepProblem StepOf(const Problem& p, const StepConstraint& constraint) {
  return {p.model.get(), ZeroState(*p.model), constraint, p.scales};
}

// The reason Accepts gives for `step` ("" when it accepts).
std::string Refusal(const Formulation& f, const StepProblem& step) {
  std::string why;
  return f.Accepts(step, &why) ? std::string() : why;
}

// Solve's std::invalid_argument message for `step` ("" when it does not throw one).
std::string SolveRefusal(Formulation& f, const StepProblem& step) {
  StartPoint start;
  start.du = Vec::Zero(step.num_dofs());
  start.r = Vec::Zero(step.num_pairs());
  try {
    f.Solve(step, start);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// A refusal: Accepts says no with `expected` as its reason, and Solve throws that reason.
void ExpectRefusal(Formulation& f, const StepProblem& step, const std::string& expected) {
  EXPECT_FALSE(f.Accepts(step));
  EXPECT_EQ(Refusal(f, step), expected);
  EXPECT_EQ(SolveRefusal(f, step), expected);
}

TEST(AcceptsTest, EquationFormulationsAndMpccsTakeEveryStep) {
  const Problem bar = MakeProblem("bar-wall");
  const fixtures::Fixture& no_energy = fixtures::FindFixture("lcp4");
  ASSERT_FALSE(no_energy.problem.model->has_energy());
  for (const char* name :
       {"implicit-fb", "nonsmooth-fb", "active-set", "ipopt-mpcc", "nlopt-merit", "nlopt-mpcc"}) {
    if (!Built(name)) continue;
    SCOPED_TRACE(name);
    auto f = Make(name);
    for (ConstraintKind kind : kAllKinds) {
      SCOPED_TRACE(ToString(kind));
      EXPECT_EQ(Refusal(*f, StepOf(bar, fixtures::ConstraintOf(kind, *bar.model))), "");
    }
    EXPECT_EQ(Refusal(*f, no_energy.Step()), "");
  }
}

TEST(AcceptsTest, ReasonIsLeftAloneOnAcceptanceAndMayBeOmitted) {
  const Problem bar = MakeProblem("bar-wall");
  const StepProblem step = StepOf(bar, StepConstraint::ArcLength(0.05));
  auto f = Make("implicit-fb");
  std::string why = "untouched";
  EXPECT_TRUE(f->Accepts(step, &why));
  EXPECT_EQ(why, "untouched");
  EXPECT_TRUE(f->Accepts(step));
}

class EnergyAcceptsTest : public ::testing::TestWithParam<std::string> {};

// An energy NLP states (9)-(11) for a given lambda: only fixed-load steps.
TEST_P(EnergyAcceptsTest, OnlyFixedLoadSteps) {
  const std::string name = GetParam();
  SKIP_UNLESS_BUILT(name);
  auto f = Make(name);
  const Problem bar = MakeProblem("bar-wall");
  for (ConstraintKind kind : kAllKinds) {
    SCOPED_TRACE(ToString(kind));
    const StepProblem step = StepOf(bar, fixtures::ConstraintOf(kind, *bar.model));
    if (kind == ConstraintKind::kFixedLoad) {
      EXPECT_EQ(Refusal(*f, step), "");
    } else {
      ExpectRefusal(*f, step,
                    name + " cannot express the step constraint '" + ToString(kind) + "'");
    }
  }
}

// A model whose internal force is not a gradient has no energy to minimise.
TEST_P(EnergyAcceptsTest, OnlyModelsWithAnEnergy) {
  const std::string name = GetParam();
  SKIP_UNLESS_BUILT(name);
  auto f = Make(name);
  const fixtures::Fixture& lcp4 = fixtures::FindFixture("lcp4");
  ASSERT_EQ(lcp4.constraint.kind, ConstraintKind::kFixedLoad);
  ExpectRefusal(*f, lcp4.Step(),
                name +
                    ": the model has no energy (has_energy() is false: its internal force is not "
                    "a gradient), so the step cannot be posed as energy minimisation; use an MPCC "
                    "or an equation formulation");
  EXPECT_EQ(Refusal(*f, fixtures::FindFixture("lcp2").Step()), "");  // symmetric: an energy
}

INSTANTIATE_TEST_SUITE_P(Energy, EnergyAcceptsTest,
                         ::testing::Values("ipopt-energy", "nlopt-energy"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// P1 at n = 10: d = 2 (n + 1)^2 = 242 unknowns, nc = 2 (n + 1) = 22 pairs.
class DenseLimitTest : public ::testing::Test {
 protected:
  void SetUp() override {
    block_ = MakeProblem("block", {{"n", "10"}});
    step_ = StepOf(block_, StepConstraint::FixedLoad(block_.load));
    d_ = step_.num_dofs();
    nc_ = step_.num_pairs();
  }
  Problem block_;
  StepProblem step_;
  int d_ = 0, nc_ = 0;
};

// nlopt-mpcc's SLSQP works on n = d + 2 nc + 1 unknowns.
TEST_F(DenseLimitTest, NloptMpccTakesUpToMaxDenseSizeUnknowns) {
  SKIP_UNLESS_BUILT("nlopt-mpcc");
  const int n = d_ + 2 * nc_ + 1;
  EXPECT_EQ(Refusal(*Make("nlopt-mpcc", {{"max_dense_size", std::to_string(n)}}), step_), "");
  auto f = Make("nlopt-mpcc", {{"max_dense_size", std::to_string(n - 1)}});
  ExpectRefusal(*f, step_,
                "nlopt-mpcc: LD_SLSQP is dense (O(n^2) memory, O(n^3) time per iteration) and "
                "this step has n = d + 2 nc + 1 = " +
                    std::to_string(n) +
                    " unknowns, above max_dense_size = " + std::to_string(n - 1));
}

// nlopt-energy with SLSQP works on the d displacements; MMA is not dense.
TEST_F(DenseLimitTest, NloptEnergySlsqpTakesUpToMaxDenseSizeUnknowns) {
  SKIP_UNLESS_BUILT("nlopt-energy");
  const std::string below = std::to_string(d_ - 1);
  EXPECT_EQ(Refusal(*Make("nlopt-energy",
                          {{"algorithm", "slsqp"}, {"max_dense_size", std::to_string(d_)}}),
                    step_),
            "");
  EXPECT_EQ(
      Refusal(*Make("nlopt-energy", {{"algorithm", "mma"}, {"max_dense_size", below}}), step_), "");
  auto f = Make("nlopt-energy", {{"algorithm", "slsqp"}, {"max_dense_size", below}});
  ExpectRefusal(*f, step_,
                "nlopt-energy: LD_SLSQP is dense (O(n^2) memory, O(n^3) time per iteration) and "
                "this step has n = " +
                    std::to_string(d_) + " unknowns, above max_dense_size = " + below +
                    " (use algorithm=mma or ccsaq)");
}

// NLopt's vector-valued constraint gradient is a dense nc x d array, whatever the algorithm.
TEST_F(DenseLimitTest, NloptEnergyTakesUpToMaxGradientEntries) {
  SKIP_UNLESS_BUILT("nlopt-energy");
  const int entries = nc_ * d_;
  EXPECT_EQ(
      Refusal(*Make("nlopt-energy", {{"max_gradient_entries", std::to_string(entries)}}), step_),
      "");
  auto f = Make("nlopt-energy", {{"max_gradient_entries", std::to_string(entries - 1)}});
  ExpectRefusal(*f, step_,
                "nlopt-energy: NLopt's vector-valued constraint needs a dense " +
                    std::to_string(nc_) + " x " + std::to_string(d_) +
                    " gradient, above max_gradient_entries = " + std::to_string(entries - 1));
}

}  // namespace
}  // namespace cb
