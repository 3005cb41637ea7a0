// The partition of the element list and of the contact pairs
// (formulations/petsc_dist/element_partition.h) and the restricted bodies it gives each process
// (ElasticBody::Restricted): every element and every pair is owned once, by the process holding
// its (node's) lowest free dof, and the restricted bodies' energies, forces and stiffnesses sum
// to the whole body's, for each element kind.
#include "formulations/petsc_dist/element_partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "problems/problem.h"

namespace cb {
namespace {

// Contiguous ranges of the body's rows, as PETSc's default layout splits them.
std::vector<int> EvenRanges(int rows, int parts) {
  std::vector<int> starts;
  for (int k = 0; k <= parts; ++k) starts.push_back(k * rows / parts + std::min(k, rows % parts));
  starts.back() = rows;
  return starts;
}

// A displacement of a few percent of the body's size, different in every component.
Vec TestDisplacement(int d, double size) {
  Vec u(d);
  for (int i = 0; i < d; ++i) u[i] = 0.03 * size * std::sin(1.0 + 0.7 * i);
  return u;
}

void ExpectPartitionSums(const std::string& problem,
                         const std::map<std::string, std::string>& parameters, int parts) {
  SCOPED_TRACE(problem + " over " + std::to_string(parts) + " processes");
  const Problem p = MakeProblem(problem, parameters);
  const ElasticBody& body = p.body->body();
  const int d = body.num_dofs();
  const std::vector<int> starts = EvenRanges(d, parts);
  const auto partition = PartitionElements(body, starts);
  ASSERT_EQ(partition.size(), static_cast<std::size_t>(parts));

  std::vector<int> owners(body.Cells().size(), 0);
  for (const auto& part : partition) {
    for (int e : part) ++owners[static_cast<std::size_t>(e)];
  }
  EXPECT_TRUE(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));

  const Vec u = TestDisplacement(d, p.scales.length);
  Vec whole_force, force_sum = Vec::Zero(d), part_force;
  body.InternalForce(u, &whole_force);
  SpMat whole_stiffness, part_stiffness;
  body.Stiffness(u, &whole_stiffness);
  Mat stiffness_sum = Mat::Zero(d, d);
  double energy_sum = 0.0;
  for (std::size_t k = 0; k < partition.size(); ++k) {
    const auto restricted = body.Restricted(partition[k]);
    EXPECT_EQ(restricted->num_dofs(), d);
    EXPECT_EQ(restricted->Cells().size(), partition[k].size());
    restricted->InternalForce(u, &part_force);
    force_sum += part_force;
    restricted->Stiffness(u, &part_stiffness);
    stiffness_sum += Mat(part_stiffness);
    energy_sum += restricted->Energy(u);
  }
  const double force_scale = whole_force.lpNorm<Eigen::Infinity>();
  EXPECT_LE((force_sum - whole_force).lpNorm<Eigen::Infinity>(), 1e-12 * force_scale);
  const Mat whole = Mat(whole_stiffness);
  EXPECT_LE((stiffness_sum - whole).lpNorm<Eigen::Infinity>(),
            1e-12 * whole.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(energy_sum, body.Energy(u), 1e-12 * std::abs(body.Energy(u)));
}

TEST(ElementPartition, PlaneStressBlockSumsToTheWholeBody) {
  ExpectPartitionSums("block", {{"n", "6"}}, 2);
  ExpectPartitionSums("block", {{"n", "6"}}, 3);
}

TEST(ElementPartition, TrussArchSumsToTheWholeBody) {
  ExpectPartitionSums("arch-flat", {}, 2);
  ExpectPartitionSums("arch-curved", {}, 3);
}

TEST(ElementPartition, SolidHexSumsToTheWholeBody) {
  ExpectPartitionSums("hertz-3d", {{"n", "3"}, {"nz", "2"}}, 2);
}

TEST(ElementPartition, ElementsGoToTheOwnerOfTheirLowestFreeDof) {
  const Problem p = MakeProblem("block", {{"n", "4"}});
  const ElasticBody& body = p.body->body();
  const std::vector<int> starts = EvenRanges(body.num_dofs(), 2);
  const auto partition = PartitionElements(body, starts);
  const auto cells = body.Cells();
  for (std::size_t k = 0; k < partition.size(); ++k) {
    for (int e : partition[k]) {
      int lowest = body.num_dofs();
      for (int node : cells[static_cast<std::size_t>(e)]) {
        for (int c = 0; c < 2; ++c) {
          if (body.dofs().dof(node, c) >= 0) lowest = std::min(lowest, body.dofs().dof(node, c));
        }
      }
      EXPECT_GE(lowest, starts[k]);
      EXPECT_LT(lowest, starts[k + 1]);
    }
  }
  EXPECT_FALSE(partition[0].empty());
  EXPECT_FALSE(partition[1].empty());
}

TEST(ElementPartition, PairsGoOnceToTheOwnerOfTheirNodesLowestFreeDof) {
  for (const Problem& p : {MakeProblem("block", {{"n", "6"}}), MakeProblem("arch-curved", {})}) {
    SCOPED_TRACE(p.name);
    const ElasticBody& body = p.body->body();
    const auto& pairs = p.body->pairs();
    const std::vector<int> starts = EvenRanges(body.num_dofs(), 3);
    const auto partition = PartitionPairs(body, pairs, starts);
    ASSERT_EQ(partition.size(), 3u);
    std::vector<int> owners(pairs.size(), 0);
    for (std::size_t k = 0; k < partition.size(); ++k) {
      EXPECT_TRUE(std::is_sorted(partition[k].begin(), partition[k].end()));
      for (int q : partition[k]) {
        ++owners[static_cast<std::size_t>(q)];
        const int node = pairs[static_cast<std::size_t>(q)].node;
        int lowest = body.num_dofs();
        for (int c = 0; c < body.dim(); ++c) {
          if (body.dofs().dof(node, c) >= 0) lowest = std::min(lowest, body.dofs().dof(node, c));
        }
        EXPECT_GE(lowest, starts[k]);
        EXPECT_LT(lowest, starts[k + 1]);
      }
    }
    EXPECT_TRUE(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
  }
}

TEST(ElementPartition, RefusesBadInput) {
  const Problem p = MakeProblem("block", {{"n", "2"}});
  const ElasticBody& body = p.body->body();
  EXPECT_THROW(body.Restricted({0, 99}), std::invalid_argument);
  EXPECT_THROW(body.Restricted({-1}), std::invalid_argument);
  EXPECT_THROW(RowOwner(body.num_dofs(), {0, body.num_dofs()}), std::invalid_argument);
  EXPECT_THROW(PartitionElements(body, {0}), std::invalid_argument);
  EXPECT_THROW(PartitionPairs(body, p.body->pairs(), {0}), std::invalid_argument);
}

}  // namespace
}  // namespace cb
