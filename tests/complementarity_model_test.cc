// The generic complementarity model: the map of an LCP / NCP onto the ContactModel interface,
// its derivatives against finite differences, the verdict as the natural residual, and the
// validation of its inputs.
#include "model/complementarity_model.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>

#include "fd_check.h"
#include "fixtures.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

Vec RandomVector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return Vec::NullaryExpr(n, [&] { return unit(rng); });
}

TEST(ComplementarityModelTest, LcpMapsOntoTheContactModel) {
  const auto model = fixtures::Lcp4Model();
  EXPECT_EQ(model->num_dofs(), 4);
  EXPECT_EQ(model->num_pairs(), 4);
  EXPECT_TRUE(model->is_linear());
  EXPECT_FALSE(model->has_energy());  // M is not symmetric
  EXPECT_EQ(model->load_pattern(), Vec::Zero(4));
  const Vec z = RandomVector(4, 1);
  Vec phi, w, reaction;
  model->Gaps(z, &phi);
  EXPECT_EQ(-phi, z);  // g = -phi = z
  model->InternalForce(z, &w);
  Mat m(4, 4);
  m << 0, 0, -1, -1, 0, 0, 1, -2, 1, -1, 2, -2, 1, 2, -2, 4;
  Vec q(4);
  q << 2, 2, -2, -6;
  EXPECT_LT((w - (m * z + q)).lpNorm<Eigen::Infinity>(), 1e-15);
  SpMat k, g, curvature;
  model->Stiffness(z, &k);
  EXPECT_EQ(Mat(k), m);
  model->GapJacobian(z, &g);
  EXPECT_EQ(Mat(g), -Mat::Identity(4, 4));
  const Vec r = RandomVector(4, 2);
  model->GeneralisedReaction(z, r, &reaction);
  EXPECT_EQ(reaction, Vec(Mat(g).transpose() * r));
  model->GapCurvature(z, r, &curvature);
  EXPECT_EQ(curvature.rows(), 4);
  EXPECT_EQ(curvature.nonZeros(), 0);
  EXPECT_THROW(model->Energy(z), std::invalid_argument);
}

TEST(ComplementarityModelTest, SymmetricLcpHasAnEnergyWhoseGradientIsTheInternalForce) {
  const auto model = fixtures::Lcp2Model();
  ASSERT_TRUE(model->has_energy());
  const Vec z = RandomVector(2, 3);
  Vec w;
  model->InternalForce(z, &w);
  const Vec fd =
      fd_check::FiniteDifferenceGradient([&](const Vec& y) { return model->Energy(y); }, z);
  EXPECT_DERIVATIVE_NEAR(Mat(w), Mat(fd), 1e-8);
  // 1/2 z^T M z + q^T z at z = (1, 0): 1 - 5.
  Vec e(2);
  e << 1.0, 0.0;
  EXPECT_DOUBLE_EQ(model->Energy(e), -4.0);
}

TEST(ComplementarityModelTest, NcpStiffnessIsTheJacobianOfFWithAFixedPattern) {
  const auto model = fixtures::KojimaShindoModel();
  EXPECT_FALSE(model->has_energy());
  EXPECT_FALSE(model->is_linear());
  for (unsigned seed : {4u, 5u}) {
    const Vec z = RandomVector(4, seed);
    SpMat k;
    model->Stiffness(z, &k);
    EXPECT_EQ(k.nonZeros(), 16);  // every entry kept, explicit zeros included
    auto f = [&](const Vec& y) {
      Vec v;
      model->InternalForce(y, &v);
      return v;
    };
    EXPECT_DERIVATIVE_NEAR(Mat(k), fd_check::FiniteDifferenceJacobian(f, z), 1e-8);
  }
  // The gap Jacobian against differences of the gaps.
  const Vec z = RandomVector(4, 6);
  SpMat g;
  model->GapJacobian(z, &g);
  auto gaps = [&](const Vec& y) {
    Vec phi;
    model->Gaps(y, &phi);
    return phi;
  };
  EXPECT_DERIVATIVE_NEAR(Mat(g), fd_check::FiniteDifferenceJacobian(gaps, z), 1e-8);
}

TEST(ComplementarityModelTest, VerdictIsTheNaturalResidualWithUnitScales) {
  // With lambda = 0 and r = -F(z), (29) holds and comp_res = ||min(z, F(z))||_inf.
  const auto model = fixtures::KojimaShindoModel();
  const Problem p = fixtures::ComplementarityProblem("ks", model);
  const Vec z = RandomVector(4, 7).cwiseAbs();
  Vec w;
  model->InternalForce(z, &w);
  StepProblem step{model.get(), ZeroState(*model), StepConstraint::FixedLoad(0.0), p.scales};
  const StepPoint point{z, z, -w, 0.0};
  const Verdict v = Judge(step, point, 1e-8);
  EXPECT_LT(v.eq_res, 1e-15);
  EXPECT_DOUBLE_EQ(v.comp_res, model->NaturalResidual(z));
  EXPECT_GT(v.comp_res, 0.0);
  // At a known solution everything vanishes.
  Vec s(4);
  s << 1.0, 0.0, 3.0, 0.0;
  model->InternalForce(s, &w);
  const Verdict at_solution = Judge(step, StepPoint{s, s, -w, 0.0}, 1e-12);
  EXPECT_TRUE(at_solution.verified);
  EXPECT_EQ(model->NaturalResidual(s), 0.0);
}

// Expects a std::invalid_argument whose message contains `field`.
template <typename F>
void ExpectRejects(F make, const std::string& field) {
  try {
    make();
    ADD_FAILURE() << "no exception; expected one naming " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(ComplementarityModelTest, ValidatesItsInputsNamingTheField) {
  ExpectRejects([] { ComplementarityModel::Lcp(Mat(2, 3), Vec(2)); }, "M");
  ExpectRejects([] { ComplementarityModel::Lcp(Mat(0, 0), Vec(0)); }, "M");
  ExpectRejects([] { ComplementarityModel::Lcp(Mat::Identity(2, 2), Vec(3)); }, "q");
  ExpectRejects(
      [] {
        Vec q(2);
        q << 1.0, std::nan("");
        ComplementarityModel::Lcp(Mat::Identity(2, 2), q);
      },
      "q");
  ExpectRejects([] { ComplementarityModel::Ncp(0, {}, {}); }, "n");
  ExpectRejects([] { ComplementarityModel::Ncp(2, {}, [](const Vec&, Mat*) {}); }, "F");
  ExpectRejects([] { ComplementarityModel::Ncp(2, [](const Vec&, Vec*) {}, {}); }, "Jacobian");
  const auto model = fixtures::Lcp2Model();
  Vec w;
  ExpectRejects([&] { model->InternalForce(Vec::Zero(3), &w); }, "u");
  // A callback returning the wrong size is reported, not read out of bounds.
  const ComplementarityModel bad = ComplementarityModel::Ncp(
      2, [](const Vec&, Vec* v) { *v = Vec::Zero(3); }, [](const Vec&, Mat* m) { *m = Mat(3, 3); });
  ExpectRejects([&] { bad.InternalForce(Vec::Zero(2), &w); }, "F");
  SpMat k;
  ExpectRejects([&] { bad.Stiffness(Vec::Zero(2), &k); }, "Jacobian");
}

}  // namespace
}  // namespace cb
