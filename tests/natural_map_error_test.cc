// The FCLIB literature's error (src/verdict/natural_map_error.h) on problems whose value is
// known in closed form: zero at the solution, and the formula's value at a chosen wrong point.
#include "verdict/natural_map_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/complementarity_model.h"
#include "model/linear_contact_model.h"
#include "problems/problem.h"

namespace cb {
namespace {

Vec Vec2(double a, double b) { return (Vec(2) << a, b).finished(); }

StepProblem FixedLoad(const ContactModel& model, double lambda) {
  State base;
  base.u = Vec::Zero(model.num_dofs());
  base.r = Vec::Zero(model.num_pairs());
  return StepProblem{&model, base, StepConstraint::FixedLoad(lambda), ContactScales{}};
}

StepPoint Point(const Vec& u, const Vec& r, double lambda) {
  StepPoint p;
  p.du = u;
  p.r = r;
  p.dlambda = lambda;
  return p;
}

// M = [2 1; 1 2], q = (-5, -6): z = (4/3, 7/3), w = 0.
const ComplementarityModel kLcp =
    ComplementarityModel::Lcp(Mat((Mat(2, 2) << 2, 1, 1, 2).finished()), Vec2(-5, -6));

TEST(NaturalMapError, LcpIsZeroAtTheSolution) {
  const Vec z = Vec2(4.0 / 3.0, 7.0 / 3.0);
  EXPECT_LE(NaturalMapError(FixedLoad(kLcp, 0.0), Point(z, Vec::Zero(2), 0.0)), 1e-15);
}

// At z = (1, 2): w = M z + q = (-1, -1), min(z, w) = (-1, -1), so sqrt(2) / ||q|| = sqrt(2/61).
// The reactions the formulation returns do not enter: u is recomputed from z, as in Siconos.
TEST(NaturalMapError, LcpIsTheMinMapOverTheNormOfQ) {
  const Vec z = Vec2(1.0, 2.0);
  const double expected = std::sqrt(2.0 / 61.0);
  EXPECT_NEAR(NaturalMapError(FixedLoad(kLcp, 0.0), Point(z, Vec::Zero(2), 0.0)), expected, 1e-15);
  EXPECT_NEAR(NaturalMapError(FixedLoad(kLcp, 0.0), Point(z, Vec::Ones(2), 0.0)), expected, 1e-15);
}

// K = diag(2, 4), one pair with normal e1 and gap u1 + 1, f = (-4, 8): contact at u = (-1, 2)
// with reaction r = -2 (K u - f = (2, 0) is pushed back by the pair).
LinearContactModel Body() {
  SpMat k(2, 2), n(2, 1);
  k.insert(0, 0) = 2.0;
  k.insert(1, 1) = 4.0;
  n.insert(0, 0) = 1.0;
  return LinearContactModel(k, n, Vec::Ones(1), Vec2(-4.0, 8.0));
}

TEST(NaturalMapError, GlobalIsZeroAtTheSolution) {
  const LinearContactModel body = Body();
  const Vec u = Vec2(-1.0, 2.0);
  EXPECT_LE(NaturalMapError(FixedLoad(body, 1.0), Point(u, Vec::Constant(1, -2.0), 1.0)), 1e-15);
}

// The reaction halved: the equilibrium residual is (1, 0), K^{-1} of it (0.5, 0); the gap is
// closed, so the contact term min(g, -r) = min(0, 1) = 0: 0.5 / (1 + ||f||) = 0.5 / (1 + sqrt 80).
TEST(NaturalMapError, GlobalIsTheVelocityErrorAndTheContactsOverOnePlusF) {
  const LinearContactModel body = Body();
  const Vec u = Vec2(-1.0, 2.0);
  EXPECT_NEAR(NaturalMapError(FixedLoad(body, 1.0), Point(u, Vec::Constant(1, -1.0), 1.0)),
              0.5 / (1.0 + std::sqrt(80.0)), 1e-15);
  // At u = 0 with no reaction: K^{-1}(-f) = (2, -2), gap 1, min(1, 0) = 0.
  EXPECT_NEAR(NaturalMapError(FixedLoad(body, 1.0), Point(Vec::Zero(2), Vec::Zero(1), 1.0)),
              std::sqrt(8.0) / (1.0 + std::sqrt(80.0)), 1e-15);
}

// K = [1 1; 1 1] (singular: the motion (1, -1) costs nothing, as a body held by its contacts
// alone moves rigidly) and a K one rounding error away from it: K^{-1} e would be rounding
// amplified, so the error is not defined.
TEST(NaturalMapError, UndefinedForASingularStiffness) {
  for (const double perturbation : {0.0, 1e-15}) {
    SpMat k(2, 2), n(2, 1);
    k.insert(0, 0) = 1.0;
    k.insert(0, 1) = 1.0;
    k.insert(1, 0) = 1.0;
    k.insert(1, 1) = 1.0 + perturbation;
    n.insert(0, 0) = 1.0;
    const LinearContactModel body(k, n, Vec::Ones(1), Vec2(-1.0, -1.0));
    EXPECT_TRUE(std::isnan(
        NaturalMapError(FixedLoad(body, 1.0), Point(Vec2(-1.0, 0.0), Vec::Zero(1), 1.0))))
        << perturbation;
  }
}

TEST(NaturalMapError, UndefinedForANonlinearModel) {
  const Problem truss = MakeProblem("two-bar", {});
  const StepProblem step = FixedLoad(*truss.model, 1.0);
  EXPECT_TRUE(std::isnan(NaturalMapError(
      step, Point(Vec::Zero(truss.model->num_dofs()), Vec::Zero(truss.model->num_pairs()), 1.0))));
}

}  // namespace
}  // namespace cb
