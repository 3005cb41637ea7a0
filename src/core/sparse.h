// Sparse assembly with a pattern analysed once.
//
// Newton-type solvers evaluate the same Jacobian structure many times. Building it from
// triplets each time costs a sort per evaluation; instead a ScatterPattern records, once, where
// each contribution lands in the compressed storage ("slot"), and later fills are a plain
// scatter-add into valuePtr(). The rule: a fill must produce the same sequence of (i, j)
// contributions as the one the pattern was built from (structural zeros included).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"

namespace cb {

class ScatterPattern {
 public:
  using Entry = std::pair<int, int>;  // (row, col)

  ScatterPattern() = default;
  // `entries` in the order a fill will add them; duplicates are summed into one slot.
  ScatterPattern(int rows, int cols, const std::vector<Entry>& entries);

  // Gives `m` this pattern with every value zero; reallocates only when `m` has another shape
  // or number of non-zeros, so a matrix filled repeatedly keeps its storage.
  void Reset(SpMat* m) const;

  // Position in m.valuePtr() of the k-th contribution.
  int slot(std::size_t k) const { return slots_[k]; }
  const std::vector<int>& slots() const { return slots_; }
  std::size_t num_entries() const { return slots_.size(); }
  const SpMat& pattern() const { return pattern_; }

 private:
  SpMat pattern_;
  std::vector<int> slots_;
};

// Entries of a sparse block placed at (row_offset, col_offset) of a larger matrix, optionally
// transposed, in the order of the block's compressed storage.
void AppendBlockEntries(const SpMat& block, int row_offset, int col_offset, bool transpose,
                        std::vector<ScatterPattern::Entry>* entries);

// Adds scale * block into `target`'s values through slots[first .. first + nnz(block)); the
// block must have the pattern it had when AppendBlockEntries was called.
void ScatterBlock(const SpMat& block, double scale, const std::vector<int>& slots,
                  std::size_t first, SpMat* target);

// What every factorisation checks of its matrix first: `a` is square (else
// std::invalid_argument, naming `who`).
void CheckSquare(const SpMat& a, const std::string& who);

// `a` in the standard compressed arrays the factorisations read: `a` itself when compressed,
// else its copy made in `scratch` (rare: a caller that inserted without makeCompressed).
const SpMat& Compressed(const SpMat& a, SpMat* scratch);

}  // namespace cb
