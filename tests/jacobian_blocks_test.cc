// Tests of src/solvers/jacobian_blocks: the block analysis of a step Jacobian's pattern, on
// small hand-built matrices and on random ones of the block form. The property: the blocks it
// finds, placed back where they belong (A's upper triangle mirrored from its lower), reassemble
// the matrix, and every stored entry is read by exactly one block; any entry outside the block
// form is refused.
#include "solvers/jacobian_blocks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/types.h"

namespace cb {
namespace {

constexpr double kCoupling = 0.3;

SpMat Compressed(int n, const std::vector<Triplet>& entries) {
  SpMat j(n, n);
  j.setFromTriplets(entries.begin(), entries.end());
  j.makeCompressed();
  return j;
}

// d = 3, nc = 2, m = 1: unknowns v = 0..2, g = 3..4, r = 5..6, y = 7. Pair 0 acts on dofs 0
// and 1, pair 1 on dof 2 and has no Da; A has no (0, 2) entry.
constexpr int kD = 3, kNc = 2, kM = 1, kN = kD + 2 * kNc + kM;
constexpr int kG = kD, kR = kD + kNc, kY = kD + 2 * kNc;

std::vector<Triplet> HandBuiltEntries() {
  // clang-format off
  return {
      {0, 0, 4.0}, {1, 0, -1.0}, {0, 1, -1.0}, {1, 1, 5.0},    // A
      {2, 1, -2.0}, {1, 2, -2.0}, {2, 2, 6.0},
      {kG, 0, 0.6}, {kG, 1, -0.8}, {kG + 1, 2, 1.0},           // G
      {0, kR, -kCoupling * 0.6}, {1, kR, kCoupling * 0.8},     // H = -coupling G^T
      {2, kR + 1, -kCoupling},
      {kG, kG, 1.0}, {kG + 1, kG + 1, 2.0},                    // E
      {kR, kG, -0.5},                                          // Da (pair 1: none)
      {kR, kR, 0.7}, {kR + 1, kR + 1, 0.9},                    // Db
      {kR, kY, 0.1}, {kR + 1, kY, 0.2},                        // U3
      {0, kY, -0.3}, {2, kY, -0.4},                            // U1
      {kY, 0, 0.01}, {kY, 2, 0.02},                            // V
      {kY, kG, -0.01}, {kY, kR + 1, -0.02},                    // Vg, Vr
      {kY, kY, -1.5},                                          // W
  };
  // clang-format on
}

// `entries` without the one at (row, col), which must be there.
std::vector<Triplet> Without(std::vector<Triplet> entries, int row, int col) {
  const auto it = std::find_if(entries.begin(), entries.end(),
                               [&](const Triplet& t) { return t.row() == row && t.col() == col; });
  EXPECT_NE(it, entries.end()) << "no entry (" << row << ", " << col << ")";
  if (it != entries.end()) entries.erase(it);
  return entries;
}

// The blocks placed back into a dense n x n matrix, A's upper triangle mirrored; `reads`
// counts how often each slot was read.
Mat Reassemble(const JacobianBlocks& b, const SpMat& j, std::vector<int>* reads) {
  const int d = b.num_dofs, nc = b.num_pairs;
  const int r2 = d, r3 = d + nc, r4 = d + 2 * nc;
  const double* val = j.valuePtr();
  reads->assign(j.nonZeros(), 0);
  Mat out = Mat::Zero(j.rows(), j.cols());
  auto put = [&](int row, int col, int slot) {
    out(row, col) = val[slot];
    ++(*reads)[slot];
  };
  for (const auto& e : b.stiffness_lower) {
    put(e.row, e.col, e.slot);
    out(e.col, e.row) = val[e.slot];
  }
  for (int p = 0; p < nc; ++p) {
    for (int s = b.pair_begin[p]; s < b.pair_begin[p + 1]; ++s) {
      put(r2 + p, b.pair_dof[s], b.g_slot[s]);
      put(b.pair_dof[s], r3 + p, b.h_slot[s]);
    }
    put(r2 + p, r2 + p, b.e_slot[p]);
    if (b.da_slot[p] >= 0) put(r3 + p, r2 + p, b.da_slot[p]);
    if (b.db_slot[p] >= 0) put(r3 + p, r3 + p, b.db_slot[p]);
  }
  for (const auto& e : b.u1) put(e.row, r4 + e.col, e.slot);
  for (const auto& e : b.u3) put(r3 + e.row, r4 + e.col, e.slot);
  for (const auto& e : b.v) put(r4 + e.row, e.col, e.slot);
  for (const auto& e : b.vg) put(r4 + e.row, r2 + e.col, e.slot);
  for (const auto& e : b.vr) put(r4 + e.row, r3 + e.col, e.slot);
  for (const auto& e : b.w) put(r4 + e.row, r4 + e.col, e.slot);
  return out;
}

// The blocks reassemble `j`, and every stored entry is read once, except those of A's strict
// upper triangle (read through their mirror).
void ExpectBlocksReassemble(const JacobianBlocks& b, const SpMat& j) {
  std::vector<int> reads;
  EXPECT_EQ(Reassemble(b, j, &reads), Mat(j));
  for (int col = 0; col < j.cols(); ++col) {
    for (int k = j.outerIndexPtr()[col]; k < j.outerIndexPtr()[col + 1]; ++k) {
      const int row = j.innerIndexPtr()[k];
      const bool upper_a = row < b.num_dofs && col < b.num_dofs && row < col;
      EXPECT_EQ(reads[k], upper_a ? 0 : 1) << "entry (" << row << ", " << col << ")";
    }
  }
}

TEST(JacobianBlocksTest, HandBuiltBlocksReassembleTheMatrix) {
  const SpMat j = Compressed(kN, HandBuiltEntries());
  const std::optional<JacobianBlocks> b = FindJacobianBlocks(j, kD, kNc);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->num_dofs, kD);
  EXPECT_EQ(b->num_pairs, kNc);
  EXPECT_EQ(b->num_border, kM);
  ExpectBlocksReassemble(*b, j);
  EXPECT_EQ(b->pair_begin, (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(b->pair_dof, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(b->stiffness_lower.size(), 5u);  // (0,0) (1,0) (1,1) (2,1) (2,2)
  EXPECT_EQ(b->da_slot[1], -1);
  for (int i = 0; i < kD; ++i) {
    ASSERT_GE(b->stiffness_diagonal_slot[i], 0);
    EXPECT_EQ(j.valuePtr()[b->stiffness_diagonal_slot[i]], j.coeff(i, i));
  }
}

TEST(JacobianBlocksTest, MissingDiagonalsAreMarked) {
  const SpMat j = Compressed(kN, Without(Without(HandBuiltEntries(), 1, 1), kR, kR));
  const std::optional<JacobianBlocks> b = FindJacobianBlocks(j, kD, kNc);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->stiffness_diagonal_slot[1], -1);
  EXPECT_EQ(b->db_slot[0], -1);
  ExpectBlocksReassemble(*b, j);
}

TEST(JacobianBlocksTest, EntriesOutsideTheBlockFormAreRefused) {
  struct Case {
    std::string what;
    int row, col;
  };
  const std::vector<Case> cases = {
      {"R3 on v", kR, 0},
      {"R2 on y", kG, kY},
      {"R1 on g", 0, kG},
      {"R2 on another pair's g", kG + 1, kG},
      {"R3 on another pair's g", kR + 1, kG},
      {"R2 on r", kG, kR},
      {"R3 on another pair's r", kR, kR + 1},
      {"H without G", 2, kR},
      {"G without H", kG, 2},
  };
  ASSERT_TRUE(FindJacobianBlocks(Compressed(kN, HandBuiltEntries()), kD, kNc).has_value());
  for (const Case& c : cases) {
    std::vector<Triplet> entries = HandBuiltEntries();
    entries.emplace_back(c.row, c.col, 1.0);
    EXPECT_FALSE(FindJacobianBlocks(Compressed(kN, entries), kD, kNc).has_value()) << c.what;
  }
}

TEST(JacobianBlocksTest, PairWithoutEIsRefused) {
  const SpMat j = Compressed(kN, Without(HandBuiltEntries(), kG + 1, kG + 1));
  EXPECT_FALSE(FindJacobianBlocks(j, kD, kNc).has_value());
}

TEST(JacobianBlocksTest, SizesThatDoNotAddUpAreRefused) {
  const SpMat j = Compressed(kN, HandBuiltEntries());
  EXPECT_FALSE(FindJacobianBlocks(j, 0, kNc).has_value());
  EXPECT_FALSE(FindJacobianBlocks(j, kD, -1).has_value());
  EXPECT_FALSE(FindJacobianBlocks(j, kD, kNc + 1).has_value());  // m = -1
}

// A random Jacobian of the block form: A symmetric with random entries (some diagonals
// missing), each pair on 1..3 distinct dofs, E always, Da, Db and the border blocks at random.
SpMat RandomBlockForm(int d, int nc, int m, std::mt19937* rng) {
  std::uniform_real_distribution<double> value(0.1, 1.0);
  std::bernoulli_distribution coin(0.5);
  std::bernoulli_distribution often(0.8);
  std::vector<Triplet> e;
  for (int col = 0; col < d; ++col) {
    if (often(*rng)) e.emplace_back(col, col, 4.0 + value(*rng));
    for (int row = col + 1; row < d; ++row) {
      if (coin(*rng)) continue;
      const double a = -value(*rng);
      e.emplace_back(row, col, a);
      e.emplace_back(col, row, a);
    }
  }
  const int r2 = d, r3 = d + nc, r4 = d + 2 * nc;
  for (int p = 0; p < nc; ++p) {
    std::set<int> dofs;
    const int count = std::uniform_int_distribution<int>(1, std::min(3, d))(*rng);
    while (static_cast<int>(dofs.size()) < count) {
      dofs.insert(std::uniform_int_distribution<int>(0, d - 1)(*rng));
    }
    for (int dof : dofs) {
      const double g = value(*rng);
      e.emplace_back(r2 + p, dof, g);
      e.emplace_back(dof, r3 + p, -kCoupling * g);
    }
    e.emplace_back(r2 + p, r2 + p, 1.0 + value(*rng));
    if (often(*rng)) e.emplace_back(r3 + p, r2 + p, -value(*rng));
    if (often(*rng)) e.emplace_back(r3 + p, r3 + p, value(*rng));
    for (int l = 0; l < m; ++l) {
      if (coin(*rng)) e.emplace_back(r3 + p, r4 + l, value(*rng));  // U3
      if (coin(*rng)) e.emplace_back(r4 + l, r2 + p, value(*rng));  // Vg
      if (coin(*rng)) e.emplace_back(r4 + l, r3 + p, value(*rng));  // Vr
    }
  }
  for (int l = 0; l < m; ++l) {
    for (int i = 0; i < d; ++i) {
      if (coin(*rng)) e.emplace_back(i, r4 + l, value(*rng));  // U1
      if (coin(*rng)) e.emplace_back(r4 + l, i, value(*rng));  // V
    }
    for (int k = 0; k < m; ++k) {
      if (often(*rng)) e.emplace_back(r4 + k, r4 + l, value(*rng));  // W
    }
  }
  return Compressed(d + 2 * nc + m, e);
}

TEST(JacobianBlocksTest, RandomBlockFormsReassemble) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const int d = std::uniform_int_distribution<int>(1, 8)(rng);
    const int nc = std::uniform_int_distribution<int>(0, 4)(rng);
    const int m = std::uniform_int_distribution<int>(0, 3)(rng);
    const SpMat j = RandomBlockForm(d, nc, m, &rng);
    const std::optional<JacobianBlocks> b = FindJacobianBlocks(j, d, nc);
    ASSERT_TRUE(b.has_value()) << "trial " << trial;
    EXPECT_EQ(b->num_border, m);
    ExpectBlocksReassemble(*b, j);
    for (int p = 0; p < nc; ++p) {
      EXPECT_TRUE(std::is_sorted(b->pair_dof.begin() + b->pair_begin[p],
                                 b->pair_dof.begin() + b->pair_begin[p + 1]));
    }
  }
}

}  // namespace
}  // namespace cb
