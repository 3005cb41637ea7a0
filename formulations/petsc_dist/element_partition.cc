#include "formulations/petsc_dist/element_partition.h"

#include <algorithm>
#include <climits>
#include <stdexcept>
#include <string>

namespace cb {

int RowOwner(int row, const std::vector<int>& row_starts) {
  if (row_starts.size() < 2 || row < row_starts.front() || row >= row_starts.back()) {
    throw std::invalid_argument("row_starts: row " + std::to_string(row) +
                                " lies outside the ranges");
  }
  const auto after = std::upper_bound(row_starts.begin(), row_starts.end(), row);
  return static_cast<int>(after - row_starts.begin()) - 1;
}

std::vector<std::vector<int>> PartitionElements(const ElasticBody& body,
                                                const std::vector<int>& row_starts) {
  if (row_starts.size() < 2) throw std::invalid_argument("row_starts: no process");
  const DofMap& dofs = body.dofs();
  const std::vector<std::vector<int>> cells = body.Cells();
  std::vector<std::vector<int>> parts(row_starts.size() - 1);
  for (std::size_t e = 0; e < cells.size(); ++e) {
    int lowest = INT_MAX;
    for (int node : cells[e]) {
      for (int c = 0; c < dofs.dim(); ++c) {
        const int dof = dofs.dof(node, c);
        if (dof >= 0) lowest = std::min(lowest, dof);
      }
    }
    const int owner = lowest == INT_MAX ? 0 : RowOwner(lowest, row_starts);
    parts[static_cast<std::size_t>(owner)].push_back(static_cast<int>(e));
  }
  return parts;
}

}  // namespace cb
