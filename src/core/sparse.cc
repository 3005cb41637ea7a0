#include "core/sparse.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cb {

namespace {

// Checks every entry and returns, per column j, the numbers k of the entries in column j in
// [start[j], start[j + 1]) of the second vector (a counting sort by column: count, prefix sum,
// fill).
std::pair<std::vector<int>, std::vector<int>> EntriesByColumn(
    int rows, int cols, const std::vector<ScatterPattern::Entry>& entries) {
  std::vector<int> start(static_cast<std::size_t>(cols) + 1, 0);
  for (const auto& [i, j] : entries) {
    if (i < 0 || i >= rows || j < 0 || j >= cols) {
      throw std::invalid_argument("ScatterPattern: entry (" + std::to_string(i) + ", " +
                                  std::to_string(j) + ") outside a " + std::to_string(rows) +
                                  " x " + std::to_string(cols) + " matrix");
    }
    ++start[j + 1];
  }
  for (int j = 0; j < cols; ++j) start[j + 1] += start[j];
  std::vector<int> next(start.begin(), start.end() - 1);
  std::vector<int> numbers;
  numbers.reserve(entries.size());
  numbers.resize(entries.size());
  for (std::size_t k = 0; k < entries.size(); ++k) {
    numbers[next[entries[k].second]++] = static_cast<int>(k);
  }
  return {std::move(start), std::move(numbers)};
}

}  // namespace

// The compressed-column pattern built directly: the entries bucketed by column, each column's
// distinct rows counted (first pass, sizing the storage once) and then written sorted, with
// each entry's slot (second pass). The result is the pattern Eigen's setFromTriplets gives
// (distinct entries, rows increasing within a column) without its row-major temporary and
// transposing copy.
ScatterPattern::ScatterPattern(int rows, int cols, const std::vector<Entry>& entries) {
  const auto [start, numbers] = EntriesByColumn(rows, cols, entries);
  std::vector<int> seen_in(rows, -1);  // the last column in which a row was met
  pattern_.resize(rows, cols);
  int* outer = pattern_.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < cols; ++j) {
    int distinct = 0;
    for (int q = start[j]; q < start[j + 1]; ++q) {
      const int i = entries[numbers[q]].first;
      if (seen_in[i] != j) {
        seen_in[i] = j;
        ++distinct;
      }
    }
    outer[j + 1] = outer[j] + distinct;
  }
  pattern_.resizeNonZeros(outer[cols]);
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + outer[cols], 0.0);
  int* inner = pattern_.innerIndexPtr();
  std::fill(seen_in.begin(), seen_in.end(), -1);
  std::vector<int> place(rows, 0);  // a row's slot in the current column
  slots_.reserve(entries.size());
  slots_.resize(entries.size());
  for (int j = 0; j < cols; ++j) {
    int end = outer[j];
    for (int q = start[j]; q < start[j + 1]; ++q) {
      const int i = entries[numbers[q]].first;
      if (seen_in[i] != j) {
        seen_in[i] = j;
        inner[end++] = i;
      }
    }
    std::sort(inner + outer[j], inner + end);
    for (int s = outer[j]; s < end; ++s) place[inner[s]] = s;
    for (int q = start[j]; q < start[j + 1]; ++q)
      slots_[numbers[q]] = place[entries[numbers[q]].first];
  }
}

void ScatterPattern::Reset(SpMat* m) const {
  // Another pattern with the same number of non-zeros must not pass for this one: compare the
  // index arrays (O(nnz), cheap next to any use of the matrix).
  const bool same =
      m->rows() == pattern_.rows() && m->cols() == pattern_.cols() &&
      m->nonZeros() == pattern_.nonZeros() && m->isCompressed() &&
      std::memcmp(pattern_.outerIndexPtr(), m->outerIndexPtr(),
                  sizeof(int) * (pattern_.outerSize() + 1)) == 0 &&
      // (An empty pattern has no index array: memcmp of a null pointer is undefined even
      // for zero bytes; UBSan.)
      (pattern_.nonZeros() == 0 || std::memcmp(pattern_.innerIndexPtr(), m->innerIndexPtr(),
                                               sizeof(int) * pattern_.nonZeros()) == 0);
  if (!same) *m = pattern_;
  std::fill(m->valuePtr(), m->valuePtr() + m->nonZeros(), 0.0);
}

void AppendBlockEntries(const SpMat& block, int row_offset, int col_offset, bool transpose,
                        std::vector<ScatterPattern::Entry>* entries) {
  for (int j = 0; j < block.outerSize(); ++j) {
    for (SpMat::InnerIterator it(block, j); it; ++it) {
      const int r = static_cast<int>(it.row());
      const int c = static_cast<int>(it.col());
      if (transpose) {
        entries->emplace_back(row_offset + c, col_offset + r);
      } else {
        entries->emplace_back(row_offset + r, col_offset + c);
      }
    }
  }
}

void ScatterBlock(const SpMat& block, double scale, const std::vector<int>& slots,
                  std::size_t first, SpMat* target) {
  double* dst = target->valuePtr();
  std::size_t k = first;
  for (int j = 0; j < block.outerSize(); ++j) {
    for (SpMat::InnerIterator it(block, j); it; ++it) dst[slots[k++]] += scale * it.value();
  }
}

void CheckSquare(const SpMat& a, const std::string& who) {
  if (a.rows() != a.cols()) {
    throw std::invalid_argument(who + ": Factorize needs a square matrix, got " +
                                std::to_string(a.rows()) + " x " + std::to_string(a.cols()));
  }
}

const SpMat& Compressed(const SpMat& a, SpMat* scratch) {
  if (a.isCompressed()) return a;
  *scratch = a;
  scratch->makeCompressed();
  return *scratch;
}

}  // namespace cb
