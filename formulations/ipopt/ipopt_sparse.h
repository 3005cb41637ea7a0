// The triplet bookkeeping of the Ipopt NLPs (ipopt_nlp.h): Ipopt takes a sparsity structure as
// (row, col) lists once and then the values in the same order at every evaluation.
#pragma once

#include <vector>

#include "core/types.h"

namespace cb {

// Appends the (row, col) of every stored entry of `m`, in compressed order, offset (of m's
// transpose when `transpose`); with `lower_only` only those on or below the diagonal of the
// result.
void AppendEntries(const SpMat& m, int row_offset, int col_offset, bool transpose, bool lower_only,
                   std::vector<int>* rows, std::vector<int>* cols);

// Writes scale * (entries of m) at values[*k...], in the order AppendEntries listed them.
void FillEntries(const SpMat& m, double scale, bool lower_only, double* values, int* k);

// Index of entry (i, j) in m's compressed storage, -1 when not stored.
int FindEntry(const SpMat& m, int i, int j);

}  // namespace cb
