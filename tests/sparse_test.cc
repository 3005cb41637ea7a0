// ScatterPattern: slots, repeated fills, and a matrix carrying another pattern.
#include "core/sparse.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "core/finite.h"

namespace cb {
namespace {

TEST(SparseTest, ScatterSumsDuplicatesIntoTheirSlots) {
  const ScatterPattern p(2, 2, {{0, 0}, {1, 1}, {0, 0}, {1, 0}});
  SpMat m;
  for (int pass = 0; pass < 2; ++pass) {
    p.Reset(&m);
    const double v[] = {1.0, 2.0, 3.0, 4.0};
    for (std::size_t k = 0; k < 4; ++k) m.valuePtr()[p.slot(k)] += v[k];
    EXPECT_EQ(m.coeff(0, 0), 4.0);
    EXPECT_EQ(m.coeff(1, 1), 2.0);
    EXPECT_EQ(m.coeff(1, 0), 4.0);
    EXPECT_EQ(m.nonZeros(), 3);
  }
}

TEST(SparseTest, ResetReplacesAnotherPatternWithTheSameNonZeroCount) {
  const ScatterPattern a(2, 2, {{0, 0}, {1, 1}});
  const ScatterPattern b(2, 2, {{0, 1}, {1, 0}});
  SpMat m;
  a.Reset(&m);
  b.Reset(&m);
  m.valuePtr()[b.slot(0)] = 5.0;
  EXPECT_EQ(m.coeff(0, 1), 5.0);
  EXPECT_EQ(m.coeff(0, 0), 0.0);
}

TEST(SparseTest, BlockEntriesTransposeAndScatter) {
  SpMat block(2, 3);
  block.insert(0, 2) = 7.0;
  block.insert(1, 0) = 3.0;
  block.makeCompressed();
  std::vector<ScatterPattern::Entry> e;
  AppendBlockEntries(block, 1, 0, true, &e);  // block^T at (1, 0) of a 4 x 2 matrix
  const ScatterPattern p(4, 2, e);
  SpMat m;
  p.Reset(&m);
  ScatterBlock(block, -2.0, p.slots(), 0, &m);
  EXPECT_EQ(m.coeff(3, 0), -14.0);
  EXPECT_EQ(m.coeff(1, 1), -6.0);
  EXPECT_THROW(ScatterPattern(2, 2, {{2, 0}}), std::invalid_argument);
}

// The pattern built directly in compressed-column form is the one Eigen's setFromTriplets
// gives (distinct entries, rows increasing in each column), and every entry's slot holds its
// own (row, column): random entries with many duplicates, empty rows and columns.
TEST(SparseTest, PatternIsSetFromTripletsPatternAndSlotsPointAtTheirEntries) {
  std::mt19937 rng(33);
  const int rows = 37, cols = 29;
  std::uniform_int_distribution<int> row(0, rows - 1), col(0, cols - 5);  // 4 empty columns
  std::vector<ScatterPattern::Entry> e;
  std::vector<Triplet> t;
  for (int k = 0; k < 600; ++k) {
    e.emplace_back(row(rng) / 2 * 2, col(rng));  // odd rows empty
    t.emplace_back(e.back().first, e.back().second, 0.0);
  }
  SpMat reference(rows, cols);
  reference.setFromTriplets(t.begin(), t.end());
  reference.makeCompressed();
  const ScatterPattern p(rows, cols, e);
  const SpMat& m = p.pattern();
  ASSERT_EQ(m.nonZeros(), reference.nonZeros());
  ASSERT_TRUE(m.isCompressed());
  for (int j = 0; j <= cols; ++j) EXPECT_EQ(m.outerIndexPtr()[j], reference.outerIndexPtr()[j]);
  for (int s = 0; s < m.nonZeros(); ++s) {
    EXPECT_EQ(m.innerIndexPtr()[s], reference.innerIndexPtr()[s]);
    EXPECT_EQ(m.valuePtr()[s], 0.0);
  }
  for (std::size_t k = 0; k < e.size(); ++k) {
    const int s = p.slot(k);
    EXPECT_EQ(m.innerIndexPtr()[s], e[k].first);
    EXPECT_TRUE(m.outerIndexPtr()[e[k].second] <= s && s < m.outerIndexPtr()[e[k].second + 1]);
  }
}

TEST(FiniteTest, AllFiniteFindsEveryKindOfNonFiniteValue) {
  std::vector<double> v = {0.0, -1.0, 1e308, std::numeric_limits<double>::denorm_min(),
                           -std::numeric_limits<double>::max()};
  EXPECT_TRUE(AllFinite(v.data(), v.size()));
  EXPECT_TRUE(AllFinite(nullptr, 0));
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    for (std::size_t at : {std::size_t{0}, std::size_t{2}, v.size() - 1}) {
      std::vector<double> w = v;
      w[at] = bad;
      EXPECT_FALSE(AllFinite(w.data(), w.size())) << bad << " at " << at;
    }
  }
}

}  // namespace
}  // namespace cb
