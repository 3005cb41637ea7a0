// The contact-only model of one process of the distributed step system
// (formulations/petsc_dist/own_pairs_model.h): over a partition of the pairs and of the rows,
// the processes' gaps, gap Jacobian rows, reactions, curvatures and loads are the whole model's,
// each pair's at its owner and the sums of the shares; with one process it is the whole
// contact-only model to the last bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "formulations/petsc_dist/element_partition.h"
#include "formulations/petsc_dist/own_pairs_model.h"
#include "problems/problem.h"

namespace cb {
namespace {

// A displacement of a few percent of the body's size and reactions of mixed sign.
Vec TestDisplacement(int d, double size) {
  Vec u(d);
  for (int i = 0; i < d; ++i) u[i] = 0.02 * size * std::sin(1.0 + 0.7 * i);
  return u;
}
Vec TestReactions(int nc) {
  Vec r(nc);
  for (int p = 0; p < nc; ++p) r[p] = std::cos(0.3 + 1.3 * p);
  return r;
}

BodyContactModel WholeContactOnly(const BodyContactModel& model) {
  return BodyContactModel(model.body().Restricted({}), model.obstacles(), model.pairs(),
                          model.load_pattern());
}

void ExpectSharesSumToTheWhole(const Problem& problem, int parts, int expected_sharing) {
  SCOPED_TRACE(problem.name + " over " + std::to_string(parts) + " processes");
  const BodyContactModel& model = *problem.body;
  const int d = model.num_dofs(), nc = model.num_pairs();
  const int rows = d + 2 * nc + 1;
  std::vector<int> starts;
  for (int k = 0; k <= parts; ++k) starts.push_back(k * rows / parts);
  const auto partition = PartitionPairs(model.body(), model.pairs(), starts);
  const BodyContactModel whole = WholeContactOnly(model);
  const Vec u = TestDisplacement(d, problem.scales.length);
  const Vec r = TestReactions(nc);

  Vec phi, reaction, load = Vec::Zero(d), reaction_sum = Vec::Zero(d);
  SpMat jacobian, curvature;
  whole.GapsAndReaction(u, r, &phi, &reaction);
  whole.GapDerivatives(u, r, &jacobian, &curvature);
  const Mat whole_jacobian = Mat(jacobian), whole_curvature = Mat(curvature);
  Mat jacobian_sum = Mat::Zero(nc, d), curvature_sum = Mat::Zero(d, d);
  int sharing = 0;
  for (int k = 0; k < parts; ++k) {
    const auto& own = partition[static_cast<std::size_t>(k)];
    if (!own.empty()) ++sharing;
    const OwnPairsModel share(model, own, starts[k], starts[k + 1]);
    EXPECT_EQ(share.num_pairs(), nc);
    Vec share_phi, share_reaction;
    SpMat share_jacobian, share_curvature;
    share.GapsReactionAndDerivatives(u, r, r, &share_phi, &share_reaction, &share_jacobian,
                                     &share_curvature);
    const Mat rows_of_share = Mat(share_jacobian);
    for (int p = 0; p < nc; ++p) {
      const bool mine = std::binary_search(own.begin(), own.end(), p);
      EXPECT_EQ(share_phi[p], mine ? phi[p] : 0.0) << "pair " << p;
      const Mat expected = mine ? Mat(whole_jacobian.row(p)) : Mat(Mat::Zero(1, d));
      EXPECT_EQ(Mat(rows_of_share.row(p)), expected) << "pair " << p;
    }
    reaction_sum += share_reaction;
    jacobian_sum += rows_of_share;
    curvature_sum += Mat(share_curvature);
    load += share.load_pattern();
  }
  EXPECT_EQ(sharing, expected_sharing);  // processes owning pairs
  const double scale = reaction.lpNorm<Eigen::Infinity>();
  EXPECT_GT(scale, 0.0);
  EXPECT_LE((reaction_sum - reaction).lpNorm<Eigen::Infinity>(), 1e-14 * scale);
  EXPECT_EQ(jacobian_sum, whole_jacobian);
  EXPECT_LE((curvature_sum - whole_curvature).lpNorm<Eigen::Infinity>(),
            1e-14 * std::max(1.0, whole_curvature.lpNorm<Eigen::Infinity>()));
  EXPECT_EQ(load, model.load_pattern());
}

TEST(DistOwnPairs, SharesSumToTheWholeModel) {
  ExpectSharesSumToTheWhole(MakeProblem("block", {{"n", "6"}}), 2, 2);
  // Curved obstacles (the curvature); the third process owns no pair.
  ExpectSharesSumToTheWhole(MakeProblem("arch-curved", {}), 3, 2);
  // 3-D; the contact face's nodes are numbered first, so the second process owns no pair.
  ExpectSharesSumToTheWhole(MakeProblem("hertz-3d", {{"n", "3"}, {"nz", "2"}}), 2, 1);
}

TEST(DistOwnPairs, OneProcessIsTheWholeContactOnlyModelToTheLastBit) {
  const Problem problem = MakeProblem("arch-curved", {});
  const BodyContactModel& model = *problem.body;
  const int d = model.num_dofs(), nc = model.num_pairs();
  std::vector<int> all(static_cast<std::size_t>(nc));
  for (int p = 0; p < nc; ++p) all[static_cast<std::size_t>(p)] = p;
  const OwnPairsModel one(model, all, 0, d + 2 * nc + 1);
  const BodyContactModel whole = WholeContactOnly(model);
  const Vec u = TestDisplacement(d, problem.scales.length);
  const Vec r = TestReactions(nc);
  Vec phi, reaction, one_phi, one_reaction, force, one_force;
  SpMat jacobian, curvature, one_jacobian, one_curvature;
  whole.GapsReactionAndDerivatives(u, r, r, &phi, &reaction, &jacobian, &curvature);
  for (int repeat = 0; repeat < 2; ++repeat) {  // the second call reuses the storage
    one.GapsReactionAndDerivatives(u, r, r, &one_phi, &one_reaction, &one_jacobian, &one_curvature);
    EXPECT_EQ(one_phi, phi);
    EXPECT_EQ(one_reaction, reaction);
    EXPECT_EQ(Mat(one_jacobian), Mat(jacobian));
    EXPECT_EQ(Mat(one_curvature), Mat(curvature));
  }
  one.Gaps(u, &one_phi);
  EXPECT_EQ(one_phi, phi);
  one.GapJacobian(u, &one_jacobian);
  EXPECT_EQ(Mat(one_jacobian), Mat(jacobian));
  one.GeneralisedReaction(u, r, &one_reaction);
  EXPECT_EQ(one_reaction, reaction);
  one.GapCurvature(u, r, &one_curvature);
  EXPECT_EQ(Mat(one_curvature), Mat(curvature));
  whole.InternalForce(u, &force);
  one.InternalForce(u, &one_force);
  EXPECT_EQ(one_force, force);
  EXPECT_EQ(one.load_pattern(), model.load_pattern());
}

TEST(DistOwnPairs, RefusesBadInput) {
  const Problem problem = MakeProblem("block", {{"n", "2"}});
  const BodyContactModel& model = *problem.body;
  const int d = model.num_dofs();
  EXPECT_THROW(OwnPairsModel(model, {model.num_pairs()}, 0, d), std::invalid_argument);
  EXPECT_THROW(OwnPairsModel(model, {1, 0}, 0, d), std::invalid_argument);
  const OwnPairsModel share(model, {0}, 0, d);
  Vec reaction;
  EXPECT_THROW(share.GeneralisedReaction(Vec::Zero(d), Vec::Zero(1), &reaction),
               std::invalid_argument);
}

}  // namespace
}  // namespace cb
