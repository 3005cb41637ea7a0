// The block form of a step Jacobian (JacobianStructure, equation_system.h), read off its
// pattern once: for every block, where its entries are stored ("slots" in valuePtr()), so that
// a solver reads the blocks of any Jacobian with that pattern without searching.
//   R1: [ A   0    H    U1 ]
//   R2: [ G   E    0    0  ]
//   R3: [ 0   Da   Db   U3 ]
//   R4: [ V   Vg   Vr   W  ]
// Only the pattern is checked here; the values (H = -coupling G^T, E non-zero) are the
// solver's to check.
#pragma once

#include <optional>
#include <vector>

#include "core/types.h"

namespace cb {

struct JacobianBlocks {
  // One stored entry: its row and column within its block, and its slot in the Jacobian.
  struct Entry {
    int row;
    int col;
    int slot;
  };

  int num_dofs = 0;    // d: the unknowns v, rows R1
  int num_pairs = 0;   // nc: the unknowns g and r, rows R2 and R3
  int num_border = 0;  // m: the unknowns y, rows R4

  // A's lower triangle (row >= col) in column-major order; A is symmetric, so its upper
  // triangle is not read.
  std::vector<Entry> stiffness_lower;
  std::vector<int> stiffness_diagonal_slot;  // per dof; -1 where A stores no diagonal entry

  // G and H by pairs: pair p's entries are s in [pair_begin[p], pair_begin[p + 1]), on the dofs
  // pair_dof[s] (increasing), G's at g_slot[s] and H's (the same dofs: H has G^T's pattern) at
  // h_slot[s].
  std::vector<int> pair_begin, pair_dof, g_slot, h_slot;
  // The diagonals per pair: E is always stored; Da and Db are -1 where not stored.
  std::vector<int> e_slot, da_slot, db_slot;

  // The border blocks in column-major order: U1 (d x m), U3 (nc x m), V (m x d), Vg and Vr
  // (m x nc), W (m x m).
  std::vector<Entry> u1, u3, v, vg, vr, w;
};

// The blocks of the compressed square `jacobian` with d = num_dofs and nc = num_pairs (then
// m = rows - d - 2 nc), or nothing when its pattern has not the block form: an entry outside
// the blocks (R2 depending on y, R3 on v, ...), a pair without its E, H's pattern not G^T's,
// or sizes that do not add up.
std::optional<JacobianBlocks> FindJacobianBlocks(const SpMat& jacobian, int num_dofs,
                                                 int num_pairs);

}  // namespace cb
