// The dense LCP of a step (formulations/siconos/siconos_lcp.h), without Siconos: the scaling of
// an LCP as it is, the elimination M = G K^-1 G^T against a closed form and against the LCP it
// inverts, the recovered points judged by the verdict, the refusals with their reasons, and the
// basis of the rigid gaps (set by the rigid space, not by the eigensolver or rounding).
#include "formulations/siconos/siconos_lcp.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <random>

#include "fixtures.h"
#include "refusal.h"
#include "siconos_test_models.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

using siconos_test::FixedLoadStep;
using siconos_test::ScaledPairs;
using siconos_test::SpringsAgainstWall;

// P1's fixed-load step at n x n elements on `model` (P1's own, or one equivalent to it).
StepProblem BlockStep(const Problem& block, const ContactModel& model) {
  return {&model, ZeroState(model), StepConstraint::FixedLoad(block.load), block.scales};
}

TEST(SiconosLcpTest, AnLcpAsGivenIsScaledByLAndR) {
  // lcp2: M = [[2, 1], [1, 2]], q = (-5, -6), z = (4/3, 7/3), w = 0 (tests/fixtures.h).
  const auto model = fixtures::Lcp2Model();
  const double length = 0.5, force = 3.0;
  const StepProblem step = FixedLoadStep(*model, 0.0, length, force);
  const SteppedLcp lcp(step);
  ASSERT_EQ(lcp.kind(), SteppedLcp::Kind::kAsGiven);
  Mat m(2, 2);
  m << 2, 1, 1, 2;
  Vec q(2);
  q << -5, -6;
  EXPECT_LE((lcp.m() - (length / force) * m).norm(), 1e-15);
  EXPECT_LE((lcp.q() - q / force).norm(), 1e-15);
  // The known z, scaled, makes w^ = 0, and its point is verified.
  Vec z(2);
  z << 4.0 / 3.0, 7.0 / 3.0;
  EXPECT_LE((lcp.m() * (z / length) + lcp.q()).norm(), 1e-14);
  const StepPoint point = lcp.PointFromZ(z / length);
  EXPECT_TRUE(Judge(step, point, 1e-12).verified);
  EXPECT_LE((point.du - z).norm(), 1e-14);
  EXPECT_LE((lcp.ZFromPoint(point.du, point.r) - z / length).norm(), 1e-15);
}

TEST(SiconosLcpTest, EliminationMatchesTheClosedFormOfTwoSprings) {
  const double k1 = 2.0, k2 = 3.0, f = 1.0, g0 = 0.5, lambda = 2.0;
  const SpringsAgainstWall model(k1, k2, f, g0);
  const double length = 0.1, force = 4.0;
  const StepProblem step = FixedLoadStep(model, lambda, length, force);
  const SteppedLcp lcp(step);
  ASSERT_EQ(lcp.kind(), SteppedLcp::Kind::kEliminatedDisplacements);
  ASSERT_EQ(lcp.size(), 1);
  // G K^-1 G^T = (K^-1)_11 = 1/k1 + 1/k2; q = -(phi(0) + G K^-1 b) = g0 - lambda f (1/k1 + 1/k2).
  const double flexibility = 1.0 / k1 + 1.0 / k2;
  EXPECT_NEAR(lcp.m()(0, 0), force / length * flexibility, 1e-12);
  EXPECT_NEAR(lcp.q()[0], (g0 - lambda * f * flexibility) / length, 1e-12);
  // In contact (lambda f flexibility = 5/3 > g0): z^ = -r / R makes w^ = g / L = 0.
  const State answer = model.Answer(lambda);
  ASSERT_LT(answer.r[0], 0.0);
  const Vec z = -answer.r / force;
  EXPECT_NEAR((lcp.m() * z + lcp.q())[0], 0.0, 1e-12);
  const StepPoint point = lcp.PointFromZ(z);
  EXPECT_TRUE(Judge(step, point, 1e-12).verified);
  EXPECT_LE((point.du - answer.u).norm(), 1e-12);
  EXPECT_NEAR(point.g[0], 0.0, 1e-12);
}

TEST(SiconosLcpTest, EliminatingAnLcpInvertsIt) {
  // Forced elimination of lcp2 (K = M, G = -I): M^ = (R / L) M^-1. Its answer has w = 0, so
  // z^ = -r / R = 0 solves the eliminated LCP, with the gap w^ = q^ = z / L.
  const auto model = fixtures::Lcp2Model();
  const double length = 2.0, force = 0.25;
  const StepProblem step = FixedLoadStep(*model, 0.0, length, force);
  const SteppedLcp lcp(step, /*eliminate=*/true);
  ASSERT_EQ(lcp.kind(), SteppedLcp::Kind::kEliminatedDisplacements);
  Mat m(2, 2);
  m << 2, 1, 1, 2;
  EXPECT_LE((lcp.m() - (force / length) * m.inverse()).norm(), 1e-12);
  const StepPoint point = lcp.PointFromZ(Vec::Zero(2));
  Vec z(2);
  z << 4.0 / 3.0, 7.0 / 3.0;
  EXPECT_LE((lcp.q() - z / length).norm(), 1e-12);
  EXPECT_LE((point.du - z).norm(), 1e-12);
  EXPECT_TRUE(Judge(step, point, 1e-12).verified);
}

TEST(SiconosLcpTest, RefusesWhatIsNoLcpWithTheReason) {
  using testing_support::Names;
  using testing_support::NamesNumber;
  const std::string name = "lcp-under-test";  // the formulation each reason names
  std::string why;
  // An arc-length step: the constraint kind named.
  const auto lcp2 = fixtures::Lcp2Model();
  StepProblem arc = FixedLoadStep(*lcp2, 0.0, 1.0, 1.0);
  arc.constraint = StepConstraint::ArcLength(0.1);
  EXPECT_FALSE(SteppedLcp::CanReduce(name, arc, 100, &why));
  EXPECT_TRUE(Names(why, {name, ToString(ConstraintKind::kArcLength)}));
  EXPECT_THROW(SteppedLcp{arc}, std::invalid_argument);
  // A nonlinear model (the bar against a wall: a truss, large deformation): its linearity.
  const fixtures::Fixture& bar = fixtures::FindFixture("bar_wall");
  EXPECT_FALSE(SteppedLcp::CanReduce(name, bar.Step(), 100, &why));
  EXPECT_TRUE(Names(why, {name, "linear"}));
  // K singular with a rigid mode the contact does not hold (no springs at all: dof 0 is free):
  // the stiffness and its rigid modes.
  const SpringsAgainstWall loose(0.0, 0.0, 1.0, 0.5);
  EXPECT_FALSE(SteppedLcp::CanReduce(name, FixedLoadStep(loose, 1.0, 1.0, 1.0), 100, &why));
  EXPECT_TRUE(Names(why, {name, "stiffness", "rigid"}));
  // The size limit, on both sides: the option, the LCP's 2 pairs and the limit 1.
  const StepProblem step = FixedLoadStep(*lcp2, 0.0, 1.0, 1.0);
  EXPECT_FALSE(SteppedLcp::CanReduce(name, step, 1, &why));
  EXPECT_TRUE(Names(why, {name, "max_size"}));
  EXPECT_TRUE(NamesNumber(why, 2));
  EXPECT_TRUE(NamesNumber(why, 1));
  EXPECT_TRUE(SteppedLcp::CanReduce(name, step, 2, &why));
}

TEST(SiconosLcpTest, ABodyHeldOnlyByItsContactKeepsItsRigidMode) {
  // k1 = 0: the springs float (K N = 0 for N = (1, 1)) and only the wall holds them. In closed
  // form u0 = u1 = g0 and r = -lambda f.
  const double k2 = 3.0, f = 1.0, g0 = 0.5, lambda = 2.0;
  const SpringsAgainstWall model(0.0, k2, f, g0);
  const double length = 0.1, force = 4.0;
  const StepProblem step = FixedLoadStep(model, lambda, length, force);
  std::string why;
  ASSERT_TRUE(SteppedLcp::CanReduce("f", step, 1, &why)) << why;
  const SteppedLcp lcp(step);
  ASSERT_EQ(lcp.kind(), SteppedLcp::Kind::kEliminatedWithRigidModes);
  ASSERT_EQ(lcp.num_rigid_modes(), 1);
  ASSERT_EQ(lcp.size(), 3);  // z^, a+^, a-^
  // The single gap is all rigid: M = 0 on it, V1 = +-1, and V1^T z^ = lambda f / R.
  const double v = lcp.m()(0, 1);
  EXPECT_NEAR(std::abs(v), 1.0, 1e-12);
  EXPECT_NEAR(lcp.m()(0, 0), 0.0, 1e-9);
  EXPECT_NEAR(v * lcp.q()[1], lambda * f / force, 1e-9);  // row a+: -V1^T z^ + e / R
  // The answer: z^ = lambda f / R, gap 0 (a = 0), w^ = 0 in every row.
  Vec z = Vec::Zero(3);
  z[0] = lambda * f / force;
  EXPECT_LE((lcp.m() * z + lcp.q()).norm(), 1e-9);
  const StepPoint point = lcp.PointFromZ(z);
  EXPECT_TRUE(Judge(step, point, 1e-9).verified);
  EXPECT_NEAR(point.du[0], g0, 1e-9);
  EXPECT_NEAR(point.du[1], g0, 1e-9);
  EXPECT_NEAR(point.r[0], -lambda * f, 1e-9);
}

TEST(SiconosLcpTest, P1KeepsItsThreeRigidModes) {
  const fixtures::Fixture& block = fixtures::FindFixture("block_n10");
  const SteppedLcp lcp(block.Step());
  EXPECT_EQ(lcp.kind(), SteppedLcp::Kind::kEliminatedWithRigidModes);
  EXPECT_EQ(lcp.num_rigid_modes(), 3);  // two translations and a rotation in the plane
  EXPECT_EQ(lcp.size(), block.problem.model->num_pairs() + 6);
  // Positive semidefinite: the rigid coupling is skew, the elastic block symmetric PSD.
  const Mat sym = 0.5 * (lcp.m() + lcp.m().transpose());
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat>(sym).eigenvalues().minCoeff(), -1e-9);
}

TEST(SiconosLcpTest, TheRigidBasisDependsOnTheRigidSpaceOnly) {
  // c A's eigenvalue 1 is triple on P1, so every orthonormal basis of the rigid gaps is an
  // eigenbasis and the eigensolver's is one that rounding picks. Any of them, turned within the
  // span, gives the LCP's basis back.
  const fixtures::Fixture& block = fixtures::FindFixture("block_n10");
  const SteppedLcp lcp(block.Step());
  const Mat& v1 = lcp.rigid_basis();
  ASSERT_EQ(v1.cols(), 3);
  EXPECT_LE((v1.transpose() * v1 - Mat::Identity(3, 3)).norm(), 1e-14);
  std::mt19937 generator(11);
  std::normal_distribution<double> normal;
  for (int turn = 0; turn < 5; ++turn) {
    Mat random(3, 3);
    for (int k = 0; k < 9; ++k) random(k % 3, k / 3) = normal(generator);
    const Mat q = Eigen::HouseholderQR<Mat>(random).householderQ();
    EXPECT_LE((SteppedLcp::CanonicalRigidBasis(Mat(v1 * q)) - v1).norm(), 1e-13) << turn;
  }
}

TEST(SiconosLcpTest, P1sLcpMovesWithItsInputNoMore) {
  // P1 (n = 20) with its pair rows scaled by 1 + O(1e-14): the same problem, perturbed at the
  // level of the rounding that the BLAS threads of the sparse solves bring into A. The triple
  // eigenvalue comes out spread by ~1e-11, and the eigensolver's basis of it moved by 2e-4 to
  // 1.5e-3 under these perturbations (q by 0.03 to 0.15 of its 34); the LCP handed to Siconos
  // now moves by about as much as its input (M by 7e-15, q by 6e-13).
  const Problem block = MakeProblem("block", {{"n", "20"}});
  const SteppedLcp lcp(BlockStep(block, *block.model));
  ASSERT_EQ(lcp.num_rigid_modes(), 3);
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const ScaledPairs model(*block.model,
                            ScaledPairs::Factors(block.model->num_pairs(), 1e-14, seed));
    const SteppedLcp other(BlockStep(block, model));
    ASSERT_EQ(other.num_rigid_modes(), 3);
    EXPECT_LE((other.rigid_basis() - lcp.rigid_basis()).lpNorm<Eigen::Infinity>(), 1e-10) << seed;
    EXPECT_LE((other.m() - lcp.m()).lpNorm<Eigen::Infinity>(),
              1e-10 * lcp.m().lpNorm<Eigen::Infinity>())
        << seed;
    EXPECT_LE((other.q() - lcp.q()).lpNorm<Eigen::Infinity>(),
              1e-10 * lcp.q().lpNorm<Eigen::Infinity>())
        << seed;
  }
}

TEST(SiconosLcpTest, TheSplitRigidRowsAreRelaxedByDelta) {
  // The rows of a+ and a- read -V1^T z^ + e / R + delta and V1^T z^ - e / R + delta: they add
  // up to 2 delta > 0 whatever z^, so no solution has both at 0 (neither ties with Lemke's z0
  // at the last pivot, and a+ a- = 0 at every solution).
  const fixtures::Fixture& block = fixtures::FindFixture("block_n10");
  const SteppedLcp lcp(block.Step());
  const int nc = block.problem.model->num_pairs();
  const int m = lcp.num_rigid_modes();
  const Vec plus = lcp.q().segment(nc, m);
  const Vec minus = lcp.q().segment(nc + m, m);
  const Vec e = 0.5 * (plus - minus);  // e / R
  const double delta = lcp.rigid_relaxation();
  const double e_max = std::max(1.0, e.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(delta, SteppedLcp::kRigidRelaxation * e_max, 1e-3 * delta);
  EXPECT_GT(delta, 0.0);
  // Up to the rounding of e / R + delta.
  EXPECT_LE(((plus + minus).array() - 2.0 * delta).abs().maxCoeff(), 1e-15 * e_max);
  // w+ + w- of the two rows for any z^: M's rows are -V1^T and V1^T (the coupling is skew).
  EXPECT_EQ(Mat(lcp.m().middleRows(nc, m) + lcp.m().middleRows(nc + m, m)).norm(), 0.0);
  // The elimination of a supported body has no such rows.
  const SpringsAgainstWall held(2.0, 3.0, 1.0, 0.5);
  EXPECT_EQ(SteppedLcp(FixedLoadStep(held, 2.0, 0.1, 4.0)).rigid_relaxation(), 0.0);
}

}  // namespace
}  // namespace cb
