#include "formulations/ipopt/ipopt_sparse.h"

#include <algorithm>

namespace cb {

void AppendEntries(const SpMat& m, int row_offset, int col_offset, bool transpose, bool lower_only,
                   std::vector<int>* rows, std::vector<int>* cols) {
  for (int j = 0; j < m.outerSize(); ++j) {
    for (SpMat::InnerIterator it(m, j); it; ++it) {
      int r = static_cast<int>(it.row()) + row_offset;
      int c = j + col_offset;
      if (transpose) {
        r = j + row_offset;
        c = static_cast<int>(it.row()) + col_offset;
      }
      if (lower_only && r < c) continue;
      rows->push_back(r);
      cols->push_back(c);
    }
  }
}

void FillEntries(const SpMat& m, double scale, bool lower_only, double* values, int* k) {
  for (int j = 0; j < m.outerSize(); ++j) {
    for (SpMat::InnerIterator it(m, j); it; ++it) {
      if (lower_only && it.row() < j) continue;
      values[(*k)++] = scale * it.value();
    }
  }
}

int FindEntry(const SpMat& m, int i, int j) {
  const int* inner = m.innerIndexPtr();
  const int* begin = inner + m.outerIndexPtr()[j];
  const int* end = inner + m.outerIndexPtr()[j + 1];
  const int* it = std::lower_bound(begin, end, i);
  if (it == end || *it != i) return -1;
  return static_cast<int>(it - inner);
}

}  // namespace cb
