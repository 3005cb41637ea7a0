// Failure handling: a NaN from the model, a singular Jacobian (a mechanism), a line
// search that cannot decrease the merit, and an Ipopt or NLopt failure are each a failed step
// with its reason (a Status and a message, the backend's return code for Ipopt and NLopt),
// never a crash or an exception, and the path driver's cut-back then decides.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "formulations/registry.h"
#include "path/path.h"
#include "problems/problem.h"
#include "refusal.h"

namespace cb {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// A model that misbehaves on purpose, wrapping a good one:
//  kNan:              energy and internal force are NaN where norm_inf(u) > limit;
//  kWrongStiffness:   the stiffness has the wrong sign (the Newton direction is not a descent
//                     direction of the merit, so the line search cannot decrease it);
//  kNoStiffness:      no energy, force or stiffness: every node not held by a contact pair is
//                     a mechanism, so the Jacobian of a step is singular.
class FaultyModel final : public ContactModel {
 public:
  enum class Fault { kNan, kWrongStiffness, kNoStiffness };
  FaultyModel(std::shared_ptr<const ContactModel> inner, Fault fault, double limit = -1.0)
      : inner_(std::move(inner)), fault_(fault), limit_(limit) {}

  int num_dofs() const override { return inner_->num_dofs(); }
  int num_pairs() const override { return inner_->num_pairs(); }
  bool has_energy() const override { return inner_->has_energy(); }
  bool is_linear() const override { return false; }
  double Energy(const Vec& u) const override { return Broken(u) ? kNan : inner_->Energy(u); }
  void InternalForce(const Vec& u, Vec* force) const override {
    inner_->InternalForce(u, force);
    if (Broken(u)) force->setConstant(kNan);
    if (fault_ == Fault::kNoStiffness) force->setZero();
  }
  void Stiffness(const Vec& u, SpMat* stiffness) const override {
    inner_->Stiffness(u, stiffness);
    *stiffness *= Sign();
  }
  std::vector<std::pair<int, int>> StiffnessEntries() const override {
    return inner_->StiffnessEntries();
  }
  void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const override {
    inner_->AddStiffness(u, Sign() * scale, slots, values);
  }
  void Gaps(const Vec& u, Vec* phi) const override { inner_->Gaps(u, phi); }
  void GapJacobian(const Vec& u, SpMat* jacobian) const override {
    inner_->GapJacobian(u, jacobian);
  }
  void GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const override {
    inner_->GeneralisedReaction(u, r, reaction);
  }
  void GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const override {
    inner_->GapCurvature(u, r, curvature);
  }
  const Vec& load_pattern() const override { return inner_->load_pattern(); }

 private:
  bool Broken(const Vec& u) const {
    return fault_ == Fault::kNan && (limit_ < 0.0 || u.lpNorm<Eigen::Infinity>() > limit_);
  }
  double Sign() const {
    if (fault_ == Fault::kNoStiffness) return 0.0;
    return fault_ == Fault::kWrongStiffness ? -1.0 : 1.0;
  }

  std::shared_ptr<const ContactModel> inner_;
  Fault fault_;
  double limit_;
};

class Collector final : public PathObserver {
 public:
  void OnAttempt(const StepAttempt& a) override { attempts.push_back(a); }
  std::vector<StepAttempt> attempts;
};

// One fixed-load step of `model` to lambda = 1, warm from the unloaded state.
StepResult FixedLoadStep(Formulation& f, const ContactModel& model, const ContactScales& scales) {
  const StepProblem step{&model, ZeroState(model), StepConstraint::FixedLoad(1.0), scales};
  StartPoint start;
  start.du = Vec::Zero(model.num_dofs());
  start.dlambda = 1.0;
  start.r = Vec::Zero(model.num_pairs());
  return f.Solve(step, start);
}

std::vector<std::string> AvailableFormulations() {
  std::vector<std::string> names;
  for (const auto& info : FormulationRegistry()) {
    if (info.available) names.push_back(info.name);
  }
  return names;
}

// Every formulation, given a model whose forces are NaN everywhere, reports a failed step with a
// reason; Ipopt's and NLopt's formulations name their backend's return code.
TEST(FailureTest, NanFromTheModelIsAFailedStepWithItsReasonInEveryFormulation) {
  const Problem p = MakeProblem("bar-wall");
  const FaultyModel model(p.model, FaultyModel::Fault::kNan);
  for (const std::string& name : AvailableFormulations()) {
    SCOPED_TRACE(name);
    auto f = MakeFormulation(name, {});
    const StepProblem step{&model, ZeroState(model), StepConstraint::FixedLoad(1.0), p.scales};
    if (!f->Accepts(step)) continue;  // an LCP backend on the nonlinear bar, say
    StepResult r;
    ASSERT_NO_THROW(r = FixedLoadStep(*f, model, p.scales));
    EXPECT_EQ(r.status, Status::kFailed) << r.message;
    EXPECT_FALSE(r.message.empty());
    if (name.rfind("ipopt", 0) == 0) {
      // details["ipopt_status"] = "<code> <Name>"; the message names it.
      const std::string code = r.details["ipopt_status"];
      ASSERT_FALSE(code.empty());
      EXPECT_LT(std::stoi(code), 0) << code;
      EXPECT_NE(r.message.find(code.substr(code.find(' ') + 1)), std::string::npos)
          << r.message << " / " << code;
    }
    if (name.rfind("nlopt", 0) == 0) {
      const std::string code = r.details["nlopt_result"];
      ASSERT_FALSE(code.empty());
      EXPECT_NE(r.message.find(code.substr(code.find(' ') + 1)), std::string::npos)
          << r.message << " / " << code;
    }
  }
}

// NaN beyond a displacement the path reaches: the step that crosses it fails with its reason,
// the driver cuts the arc length back and the path stops with kFailed, without throwing.
TEST(FailureTest, NanOnThePathIsCutBackThenStopsTheRun) {
  const Problem p = MakeProblem("bar-wall");
  const double limit = 0.5 * p.parameters.Real("gap");
  const FaultyModel model(p.model, FaultyModel::Fault::kNan, limit);
  auto f = MakeFormulation("implicit-fb", {});
  Collector c;
  PathOptions o;
  o.arc_length = p.arc_length;
  o.max_steps = 4 * p.steps;
  PathSummary s;
  ASSERT_NO_THROW(s = TraceArcLengthPath(model, p.scales, ZeroState(model), *f, o, &c));
  EXPECT_EQ(s.status, Status::kFailed) << s.message;
  // The reason gives the step that failed and the cut-backs it ran out of.
  EXPECT_TRUE(testing_support::NamesNumber(s.message, s.accepted_steps + 1));
  EXPECT_TRUE(testing_support::NamesNumber(s.message, o.max_cutbacks));
  ASSERT_GE(c.attempts.size(), 2u);
  // The failed attempts carry the solver's reason; a failed attempt is followed by a retry with
  // half the arc length (the cut-back), up to max_cutbacks.
  int retries = 0;
  for (std::size_t k = 0; k < c.attempts.size(); ++k) {
    const StepAttempt& a = c.attempts[k];
    if (a.accepted) {
      EXPECT_LE(a.state.u.lpNorm<Eigen::Infinity>(), limit);
      continue;
    }
    EXPECT_FALSE(a.verdict.verified);
    EXPECT_FALSE(a.result.message.empty()) << "step " << a.step;
    if (k + 1 < c.attempts.size() && c.attempts[k + 1].step == a.step) {
      ++retries;
      EXPECT_EQ(c.attempts[k + 1].attempt, a.attempt + 1);
      EXPECT_DOUBLE_EQ(c.attempts[k + 1].arc_length, 0.5 * a.arc_length);
    }
  }
  EXPECT_GE(retries, o.max_cutbacks);
  const StepAttempt& last = c.attempts.back();
  EXPECT_FALSE(last.accepted);
  EXPECT_EQ(last.attempt, o.max_cutbacks);
  // The path got as far as the limit allows before giving up.
  EXPECT_GT(s.accepted_steps, 0);
  EXPECT_LE(s.final_state.u.lpNorm<Eigen::Infinity>(), limit);
}

TEST(FailureTest, SingularJacobianIsAFailedStepWithItsReason) {
  const Problem p = MakeProblem("arch-curved");
  const FaultyModel model(p.model, FaultyModel::Fault::kNoStiffness);
  for (const std::string solver : {"newton", "quasi-newton"}) {
    SCOPED_TRACE(solver);
    FormulationConfig config;
    config.solver = solver;
    auto f = MakeFormulation("implicit-fb", config);
    StepResult r;
    ASSERT_NO_THROW(r = FixedLoadStep(*f, model, p.scales));
    EXPECT_EQ(r.status, Status::kFailed) << r.message;
    EXPECT_NE(r.message.find("singular"), std::string::npos) << r.message;
  }
  // The path driver: the fixed-load solve is reported as not verified, with the reason.
  auto f = MakeFormulation("implicit-fb", {});
  Collector c;
  PathSummary s;
  ASSERT_NO_THROW(s = SolveFixedLoad(model, p.scales, ZeroState(model), 1.0, *f, {}, &c));
  EXPECT_EQ(s.status, Status::kFailed);
  EXPECT_NE(s.message.find("singular"), std::string::npos) << s.message;
  ASSERT_EQ(c.attempts.size(), 1u);
  EXPECT_FALSE(c.attempts[0].accepted);
}

TEST(FailureTest, SingularTangentStopsTheArcLengthPathWithItsReason) {
  const Problem p = MakeProblem("arch-curved");
  const FaultyModel model(p.model, FaultyModel::Fault::kNoStiffness);
  auto f = MakeFormulation("implicit-fb", {});
  Collector c;
  PathOptions o;
  o.arc_length = p.arc_length;
  o.max_steps = 5;
  PathSummary s;
  ASSERT_NO_THROW(s = TraceArcLengthPath(model, p.scales, ZeroState(model), *f, o, &c));
  EXPECT_EQ(s.status, Status::kFailed);
  EXPECT_NE(s.message.find("singular"), std::string::npos) << s.message;
  EXPECT_EQ(s.accepted_steps, 0);
}

// The stiffness with the wrong sign: the Newton direction does not decrease the merit, so the
// Armijo line search runs out of trials; Newton reports that, and the cut-backs then run out.
TEST(FailureTest, LineSearchThatCannotDecreaseTheMeritIsAFailedStep) {
  const Problem p = MakeProblem("bar-wall");
  const FaultyModel model(p.model, FaultyModel::Fault::kWrongStiffness);
  auto f = MakeFormulation("implicit-fb", {});
  StepResult r;
  ASSERT_NO_THROW(r = FixedLoadStep(*f, model, p.scales));
  EXPECT_EQ(r.status, Status::kFailed) << r.message;
  const bool named = r.message.find("line search") != std::string::npos ||
                     r.message.find("stagnation") != std::string::npos;
  EXPECT_TRUE(named) << r.message;

  Collector c;
  PathOptions o;
  o.arc_length = p.arc_length;
  o.max_steps = 3;
  o.max_cutbacks = 2;
  PathSummary s;
  ASSERT_NO_THROW(s = TraceArcLengthPath(model, p.scales, ZeroState(model), *f, o, &c));
  EXPECT_EQ(s.status, Status::kFailed) << s.message;
  ASSERT_EQ(c.attempts.size(), 3u);  // the first step and its two cut-backs
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(c.attempts[k].attempt, k);
    EXPECT_FALSE(c.attempts[k].accepted);
    EXPECT_FALSE(c.attempts[k].result.message.empty());
  }
}

}  // namespace
}  // namespace cb
