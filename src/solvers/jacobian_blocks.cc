#include "solvers/jacobian_blocks.h"

#include <cstddef>
#include <utility>

namespace cb {
namespace {

// Per pair, the (index, slot) of its entries in one row of G or one column of H.
using PairEntries = std::vector<std::vector<std::pair<int, int>>>;

// Files every stored entry under its block (rows and columns in the order of the block form:
// v, g, r, y). G's rows and H's columns are collected per pair, for PairUp. False at the first
// entry outside the blocks.
bool ClassifyEntries(const SpMat& j, JacobianBlocks* blocks, PairEntries* g_rows,
                     PairEntries* h_cols) {
  const int d = blocks->num_dofs, nc = blocks->num_pairs;
  const int n = static_cast<int>(j.rows());
  const int r2 = d, r3 = d + nc, r4 = d + 2 * nc;
  const int* outer = j.outerIndexPtr();
  const int* inner = j.innerIndexPtr();
  for (int col = 0; col < n; ++col) {
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      const int row = inner[k];
      if (col < d) {  // v columns
        if (row < d) {
          if (row >= col) {
            blocks->stiffness_lower.push_back({row, col, k});
            if (row == col) blocks->stiffness_diagonal_slot[col] = k;
          }
        } else if (row < r3) {
          (*g_rows)[row - r2].emplace_back(col, k);
        } else if (row < r4) {
          return false;  // R3 must not depend on v
        } else {
          blocks->v.push_back({row - r4, col, k});
        }
      } else if (col < r3) {  // g columns
        const int p = col - d;
        if (row == r2 + p) {
          blocks->e_slot[p] = k;
        } else if (row == r3 + p) {
          blocks->da_slot[p] = k;
        } else if (row >= r4) {
          blocks->vg.push_back({row - r4, p, k});
        } else {
          return false;
        }
      } else if (col < r4) {  // r columns
        const int p = col - r3;
        if (row < d) {
          (*h_cols)[p].emplace_back(row, k);
        } else if (row == r3 + p) {
          blocks->db_slot[p] = k;
        } else if (row >= r4) {
          blocks->vr.push_back({row - r4, p, k});
        } else {
          return false;
        }
      } else {  // border columns
        const int l = col - r4;
        if (row < d) {
          blocks->u1.push_back({row, l, k});
        } else if (row >= r3 && row < r4) {
          blocks->u3.push_back({row - r3, l, k});
        } else if (row >= r4) {
          blocks->w.push_back({row - r4, l, k});
        } else {
          return false;  // R2 must not depend on y
        }
      }
    }
  }
  return true;
}

// G by pairs (each row's entries by increasing dof, as the scan is column-major), and H beside
// it: H = -coupling G^T must have G^T's pattern. False for a pair without E or a mismatch.
bool PairUp(const PairEntries& g_rows, const PairEntries& h_cols, JacobianBlocks* blocks) {
  const int nc = blocks->num_pairs;
  blocks->pair_begin.assign(nc + 1, 0);
  for (int p = 0; p < nc; ++p) {
    if (blocks->e_slot[p] < 0) return false;
    if (h_cols[p].size() != g_rows[p].size()) return false;
    for (std::size_t q = 0; q < g_rows[p].size(); ++q) {
      if (h_cols[p][q].first != g_rows[p][q].first) return false;
      blocks->pair_dof.push_back(g_rows[p][q].first);
      blocks->g_slot.push_back(g_rows[p][q].second);
      blocks->h_slot.push_back(h_cols[p][q].second);
    }
    blocks->pair_begin[p + 1] = static_cast<int>(blocks->pair_dof.size());
  }
  return true;
}

// The number of A's lower-triangle entries, so that stiffness_lower is sized once (grown by
// doubling, its ~3e6 entries at P1 n = 400 were copied into fresh pages ~20 times).
std::size_t CountLowerStiffness(const SpMat& j, int d) {
  const int* outer = j.outerIndexPtr();
  const int* inner = j.innerIndexPtr();
  std::size_t count = 0;
  for (int col = 0; col < d && col < j.outerSize(); ++col) {
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      if (inner[k] >= col && inner[k] < d) ++count;
    }
  }
  return count;
}

}  // namespace

std::optional<JacobianBlocks> FindJacobianBlocks(const SpMat& jacobian, int num_dofs,
                                                 int num_pairs) {
  JacobianBlocks blocks;
  blocks.num_dofs = num_dofs;
  blocks.num_pairs = num_pairs;
  blocks.num_border = static_cast<int>(jacobian.rows()) - num_dofs - 2 * num_pairs;
  if (num_dofs <= 0 || num_pairs < 0 || blocks.num_border < 0) return std::nullopt;
  blocks.stiffness_diagonal_slot.assign(num_dofs, -1);
  blocks.e_slot.assign(num_pairs, -1);
  blocks.da_slot.assign(num_pairs, -1);
  blocks.db_slot.assign(num_pairs, -1);
  blocks.stiffness_lower.reserve(CountLowerStiffness(jacobian, num_dofs));
  PairEntries g_rows(num_pairs), h_cols(num_pairs);
  if (!ClassifyEntries(jacobian, &blocks, &g_rows, &h_cols)) return std::nullopt;
  if (!PairUp(g_rows, h_cols, &blocks)) return std::nullopt;
  return blocks;
}

}  // namespace cb
