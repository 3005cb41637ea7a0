// The stiffness pattern of a body of elements (Q4, hexahedra), built directly in compressed
// column form with O(nnz) memory: K(i, j) is structurally non-zero iff the nodes of dofs i and
// j share an element. A triplet list would hold (nodes per element * dim)^2 entries per
// element (10^7 for the 400 x 400 mesh of P1) and sort them.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "core/types.h"
#include "model/elastic_body.h"

namespace cb {

// The pattern of K over `dofs` (supported components have no dof), its values zero. Columns
// follow the dof numbering, which is increasing in (node, component); rows within a column
// come out sorted because the node adjacency lists are.
template <std::size_t N>
SpMat ElementStiffnessPattern(const DofMap& dofs, const std::vector<std::array<int, N>>& elements) {
  constexpr int kPer = static_cast<int>(N);
  const int nodes = dofs.num_nodes();
  const int dim = dofs.dim();
  // Node adjacency (self included) as CSR, from the elements, then sorted and deduplicated.
  std::vector<int> adj_start(nodes + 1, 0);
  for (const auto& el : elements) {
    for (int a = 0; a < kPer; ++a) adj_start[el[a] + 1] += kPer;
  }
  for (int n = 0; n < nodes; ++n) adj_start[n + 1] += adj_start[n];
  std::vector<int> adj(adj_start[nodes]);
  {
    std::vector<int> cursor(adj_start.begin(), adj_start.end() - 1);
    for (const auto& el : elements) {
      for (int a = 0; a < kPer; ++a) {
        for (int b = 0; b < kPer; ++b) adj[cursor[el[a]]++] = el[b];
      }
    }
  }
  std::vector<int> adj_count(nodes, 0);
  std::size_t estimate = 0;
  for (int n = 0; n < nodes; ++n) {
    auto first = adj.begin() + adj_start[n];
    auto last = adj.begin() + adj_start[n + 1];
    std::sort(first, last);
    adj_count[n] = static_cast<int>(std::unique(first, last) - first);
    estimate += static_cast<std::size_t>(dim * dim) * static_cast<std::size_t>(adj_count[n]);
  }
  const int d = dofs.num_dofs();
  std::vector<int> outer(d + 1, 0);
  std::vector<int> inner;
  inner.reserve(estimate);
  for (int n = 0; n < nodes; ++n) {
    for (int c = 0; c < dim; ++c) {
      const int j = dofs.dof(n, c);
      if (j < 0) continue;
      for (int k = 0; k < adj_count[n]; ++k) {
        const int m = adj[adj_start[n] + k];
        for (int c2 = 0; c2 < dim; ++c2) {
          const int i = dofs.dof(m, c2);
          if (i >= 0) inner.push_back(i);
        }
      }
      outer[j + 1] = static_cast<int>(inner.size());
    }
  }
  SpMat pattern(d, d);
  pattern.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), pattern.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), pattern.innerIndexPtr());
  std::fill(pattern.valuePtr(), pattern.valuePtr() + inner.size(), 0.0);
  return pattern;
}

}  // namespace cb
