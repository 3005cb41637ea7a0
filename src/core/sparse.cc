#include "core/sparse.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace cb {

ScatterPattern::ScatterPattern(int rows, int cols, const std::vector<Entry>& entries) {
  std::vector<Triplet> triplets;
  triplets.reserve(entries.size());
  for (const auto& [i, j] : entries) {
    if (i < 0 || i >= rows || j < 0 || j >= cols) {
      throw std::invalid_argument("ScatterPattern: entry (" + std::to_string(i) + ", " +
                                  std::to_string(j) + ") outside a " + std::to_string(rows) +
                                  " x " + std::to_string(cols) + " matrix");
    }
    triplets.emplace_back(i, j, 0.0);
  }
  pattern_.resize(rows, cols);
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  slots_.reserve(entries.size());
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  for (const auto& [i, j] : entries) {
    const int* first = inner + outer[j];
    const int* last = inner + outer[j + 1];
    const int* it = std::lower_bound(first, last, i);
    slots_.push_back(static_cast<int>(it - inner));
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
