// The stopping test at the rounding floor (EquationSystem::ResidualFloor): a solver that cannot
// go on at a point whose rows are all within their floor reports it converged, and only then.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "formulations/implicit_fb/implicit_fb.h"
#include "model/body_contact_model.h"
#include "model/obstacle.h"
#include "model/truss.h"
#include "path/path.h"
#include "problems/problem.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

// F(x) = x - 1/3 + 1e-9 sin(1e12 x), J = 1: the sine stands for rounding, a term the Jacobian
// does not see that changes faster than any step can follow, so no solver gets |F| below
// ~1e-9 (its floor) while the absolute test asks for 1e-10.
class NoisySystem : public EquationSystem {
 public:
  explicit NoisySystem(bool knows_floor) : knows_floor_(knows_floor) {}
  int size() const override { return 1; }
  bool Residual(const Vec& x, Vec* f) override {
    f->resize(1);
    (*f)[0] = x[0] - 1.0 / 3.0 + 1e-9 * std::sin(1e12 * x[0]);
    return true;
  }
  void Jacobian(const Vec& /*x*/, SpMat* j) override {
    const std::vector<Triplet> entries = {{0, 0, 1.0}};
    j->resize(1, 1);
    j->setFromTriplets(entries.begin(), entries.end());
  }
  bool ResidualFloor(const Vec& /*x*/, Vec* floor) override {
    if (!knows_floor_) return false;
    *floor = Vec::Constant(1, 2e-9);
    return true;
  }

 private:
  bool knows_floor_;
};

TEST(RoundingFloorTest, AStuckSolverIsConvergedOnlyWithinTheFloor) {
  for (const char* name : {"newton", "dogleg", "quasi-newton"}) {
    SCOPED_TRACE(name);
    SolverOptions options;
    options.max_iterations = 50;
    NoisySystem unknown(false), known(true);
    Vec x = Vec::Constant(1, 1.0);
    const SolverSummary without = MakeEquationSolver(name, options)->Solve(unknown, &x);
    EXPECT_NE(without.status, Status::kConverged) << without.message;
    EXPECT_GT(without.final_residual_inf, options.residual_tol);
    x = Vec::Constant(1, 1.0);
    const SolverSummary with = MakeEquationSolver(name, options)->Solve(known, &x);
    EXPECT_EQ(with.status, Status::kConverged) << with.message;
    EXPECT_NE(with.message.find("rounding floor"), std::string::npos) << with.message;
    EXPECT_LE(with.final_residual_inf, 2e-9);
    EXPECT_NEAR(x[0], 1.0 / 3.0, 3e-9);
  }
}

// The two-bar truss pressed onto a floor under its apex (the apex moves vertically only), with
// bars of axial stiffness `ea` and an apex load `load` per unit lambda.
std::unique_ptr<BodyContactModel> TwoBarOnAFloor(double ea, double load) {
  Mat xy(3, 2);
  xy << -1.0, 0.0, 0.0, 0.5, 1.0, 0.0;
  auto body =
      std::make_shared<Truss>(xy, std::vector<TrussMember>{{0, 1, ea, 1.0}, {1, 2, ea, 1.0}},
                              std::vector<bool>{true, true, true, false, true, true});
  Point surface(2), down(2);
  surface << 0.0, 0.45;
  down << 0.0, -1.0;
  Vec f = Vec::Zero(body->num_dofs());
  f[body->dofs().dof(1, 1)] = -load;
  return std::make_unique<BodyContactModel>(
      body,
      std::vector<std::shared_ptr<const Obstacle>>{std::make_shared<HalfSpace>(surface, down)},
      std::vector<ContactPair>{{1, 0}}, f);
}

// implicit-fb's step at lambda = 1 (the apex on the floor, 0.05 down). With the force scale R
// of the forces the absolute test is met. With R 1e8 times too small the scaled reaction is
// ~1e8 and Newton stalls far from the answer: the rows of (29) are then far above their floor
// (which the stuck solve consults), so the step is not reported converged, and the verdict
// agrees. Found and verified agree both ways.
TEST(RoundingFloorTest, FoundAndVerifiedAgreeWhateverTheForceScale) {
  for (const double force_scale : {1e16, 1e8}) {
    SCOPED_TRACE("R = " + std::to_string(force_scale));
    const auto model = TwoBarOnAFloor(1e17, 1e16);
    const StepProblem step{
        model.get(), ZeroState(*model), StepConstraint::FixedLoad(1.0), {0.1, force_scale}};
    ImplicitFbOptions o;
    o.solver = "newton";
    ImplicitFb formulation(o);
    StartPoint warm;  // from the unloaded state
    warm.du = Vec::Zero(1);
    warm.dlambda = 1.0;
    warm.r = Vec::Zero(1);
    const StepResult result = formulation.Solve(step, warm);
    const bool found = result.status == Status::kConverged;
    EXPECT_EQ(found, Judge(step, result.point, 1e-8).verified) << result.message;
    EXPECT_EQ(found, force_scale == 1e16) << result.message;
    EXPECT_EQ(result.message.find("rounding floor"), std::string::npos) << result.message;
    if (found) {
      EXPECT_NEAR(result.point.du[0], -0.05, 1e-9);  // the apex's height, from 0.5
    }
  }
}

// The magnitudes bound the force they add up, and equal it where a row has one term.
TEST(RoundingFloorTest, InternalForceMagnitudesBoundTheForce) {
  const auto model = TwoBarOnAFloor(10.0, 1.0);
  const Vec u = Vec::Constant(1, -0.3);
  Vec force, magnitudes;
  model->InternalForce(u, &force);
  model->InternalForceMagnitudes(u, &magnitudes);
  ASSERT_EQ(magnitudes.size(), 1);
  // The apex row sums the two bars' equal vertical pulls: no cancellation, so |f| itself.
  EXPECT_NEAR(magnitudes[0], std::abs(force[0]), 1e-14 * std::abs(force[0]));
  EXPECT_GT(std::abs(force[0]), 0.0);
}

// On every kind of body (Q4 by |K| |u|, the truss's members, the neo-Hookean hexahedra's
// elements) the magnitudes bound |f_int| row by row at a displaced state.
TEST(RoundingFloorTest, InternalForceMagnitudesBoundTheForceOnEveryBody) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const char* name : {"block", "arch-curved", "plate-3d"}) {
    SCOPED_TRACE(name);
    const Problem p = MakeProblem(name, {});
    Vec u(p.model->num_dofs());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = 0.01 * unit(rng);
    Vec force, magnitudes;
    p.model->InternalForce(u, &force);
    p.model->InternalForceMagnitudes(u, &magnitudes);
    ASSERT_EQ(magnitudes.size(), force.size());
    EXPECT_TRUE(
        (magnitudes.array() >= force.cwiseAbs().array() - 1e-12 * magnitudes.array()).all());
    EXPECT_GT(magnitudes.maxCoeff(), 0.0);
  }
}

}  // namespace
}  // namespace cb
