// The pieces of a distributed run's VTK output (bench/harness/vtk_pieces.h): over the pieces of
// every process, each element once and each node once as its owner's, a piece holding the nodes
// of its elements, and a node shared by pieces owned by the lowest of their processes.
#include "harness/vtk_pieces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "formulations/petsc_dist/element_partition.h"
#include "problems/problem.h"

namespace cb::harness {
namespace {

// The block (P1) of n x n Q4 elements.
Problem Block(int n) { return MakeProblem("block", {{"n", std::to_string(n)}}); }

// The element partition of three processes over the body's rows, as the distributed system
// makes it (element_partition.h).
std::vector<std::vector<int>> ThreeParts(const ElasticBody& body) {
  const int d = body.num_dofs();
  return PartitionElements(body, {0, d / 3, 2 * d / 3, d});
}

TEST(VtkPiecesTest, EveryElementOnceAndEveryNodeOnceAsItsOwners) {
  const Problem problem = Block(6);
  const ElasticBody& body = problem.body->body();
  const auto parts = ThreeParts(body);
  const auto cells = body.Cells();
  std::multiset<int> all_cells;
  std::multiset<int> owned_nodes;
  std::map<int, int> owner;  // node -> the process whose piece owns it
  int duplicates = 0;
  for (int p = 0; p < 3; ++p) {
    const BodyPiece piece = PieceOfProcess(body, parts, p, 3);
    EXPECT_EQ(piece.cells, parts[p]);
    ASSERT_EQ(piece.nodes.size(), piece.duplicate.size());
    EXPECT_TRUE(std::is_sorted(piece.nodes.begin(), piece.nodes.end()));
    const std::set<int> nodes(piece.nodes.begin(), piece.nodes.end());
    for (int c : piece.cells) {
      all_cells.insert(c);
      for (int node : cells[c]) EXPECT_TRUE(nodes.count(node)) << "cell " << c << " node " << node;
    }
    for (std::size_t k = 0; k < piece.nodes.size(); ++k) {
      if (piece.duplicate[k]) {
        ++duplicates;
        continue;
      }
      owned_nodes.insert(piece.nodes[k]);
      owner[piece.nodes[k]] = p;
    }
  }
  EXPECT_EQ(all_cells.size(), cells.size());
  EXPECT_EQ(std::set<int>(all_cells.begin(), all_cells.end()).size(), cells.size());
  EXPECT_EQ(owned_nodes.size(), static_cast<std::size_t>(body.num_nodes()));
  EXPECT_EQ(std::set<int>(owned_nodes.begin(), owned_nodes.end()).size(), owned_nodes.size());
  EXPECT_GT(duplicates, 0);  // three pieces of one block share the nodes of their borders
  // The owner is the lowest process among those whose elements use the node.
  for (int p = 0; p < 3; ++p) {
    for (int c : parts[p]) {
      for (int node : cells[c]) EXPECT_LE(owner[node], p) << "node " << node;
    }
  }
}

TEST(VtkPiecesTest, WithoutAPartitionProcessZeroHoldsTheWholeBody) {
  const Problem problem = Block(3);
  const ElasticBody& body = problem.body->body();
  const BodyPiece zero = PieceOfProcess(body, {}, 0, 2);
  EXPECT_EQ(zero.cells.size(), body.Cells().size());
  EXPECT_EQ(zero.nodes.size(), static_cast<std::size_t>(body.num_nodes()));
  EXPECT_EQ(std::count(zero.duplicate.begin(), zero.duplicate.end(), true), 0);
  const BodyPiece one = PieceOfProcess(body, {}, 1, 2);
  EXPECT_TRUE(one.cells.empty());
  EXPECT_TRUE(one.nodes.empty());
}

TEST(VtkPiecesTest, RefusesAProcessOutsideTheRunAndAPartitionOfAnotherSize) {
  const Problem problem = Block(3);
  const ElasticBody& body = problem.body->body();
  EXPECT_THROW(PieceOfProcess(body, {}, 2, 2), std::invalid_argument);
  EXPECT_THROW(PieceOfProcess(body, ThreeParts(body), 0, 2), std::invalid_argument);
}

TEST(VtkPiecesTest, PieceFilesAreNamedByStateAndProcess) {
  EXPECT_EQ(PieceFile("block_0003", 1), "block_0003_p1.vtu");
}

}  // namespace
}  // namespace cb::harness
