#include "formulations/petsc_dist/element_partition.h"

#include <algorithm>
#include <climits>
#include <stdexcept>
#include <string>

namespace cb {

namespace {

// The process holding the lowest free dof of `nodes` (process 0 when none is free).
template <typename Nodes>
int OwnerOfNodes(const DofMap& dofs, const Nodes& nodes, const std::vector<int>& row_starts) {
  int lowest = INT_MAX;
  for (int node : nodes) {
    for (int c = 0; c < dofs.dim(); ++c) {
      const int dof = dofs.dof(node, c);
      if (dof >= 0) lowest = std::min(lowest, dof);
    }
  }
  return lowest == INT_MAX ? 0 : RowOwner(lowest, row_starts);
}

void RequireProcesses(const std::vector<int>& row_starts) {
  if (row_starts.size() < 2) throw std::invalid_argument("row_starts: no process");
}

}  // namespace

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
  RequireProcesses(row_starts);
  const std::vector<std::vector<int>> cells = body.Cells();
  std::vector<std::vector<int>> parts(row_starts.size() - 1);
  for (std::size_t e = 0; e < cells.size(); ++e) {
    const int owner = OwnerOfNodes(body.dofs(), cells[e], row_starts);
    parts[static_cast<std::size_t>(owner)].push_back(static_cast<int>(e));
  }
  return parts;
}

std::vector<std::vector<int>> PartitionPairs(const ElasticBody& body,
                                             const std::vector<ContactPair>& pairs,
                                             const std::vector<int>& row_starts) {
  RequireProcesses(row_starts);
  std::vector<std::vector<int>> parts(row_starts.size() - 1);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const int node[] = {pairs[p].node};
    const int owner = OwnerOfNodes(body.dofs(), node, row_starts);
    parts[static_cast<std::size_t>(owner)].push_back(static_cast<int>(p));
  }
  return parts;
}

}  // namespace cb
