// The nodes of a body problem file: the table of node ids, the checks that no two nodes share
// a place and no element is listed twice, and the direction names of supports and controls.
// Internal to the problem-file reader.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "core/types.h"
#include "io/json_node.h"

namespace cb::io::reading {

// Nodes by id: ids are any integers, unique; the body numbers nodes by position.
struct NodeTable {
  std::vector<std::int64_t> ids;
  std::map<std::int64_t, int> index;
  Mat coordinates;

  int Find(const JsonNode& ref) const;
};

// A pair of nodes at the same place (within 1e-12 of the nodes' extent), or nothing: a node
// written twice leaves the elements on either copy unconnected, with no word from the model.
std::optional<std::pair<int, int>> CoincidentNodes(const Mat& xy);

// The first element that has the same nodes as an earlier one, with that earlier one, or
// nothing: a hexahedron listed twice doubles its stiffness with no word from the model (and
// makes its faces interior, so a traction on them is refused for another reason).
template <typename Element>
std::optional<std::pair<std::size_t, std::size_t>> DuplicateElement(
    const std::vector<Element>& elements) {
  std::map<Element, std::size_t> first;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    Element sorted = elements[k];
    std::sort(sorted.begin(), sorted.end());
    const auto [it, added] = first.emplace(sorted, k);
    if (!added) return std::make_pair(it->second, k);
  }
  return std::nullopt;
}

// "nodes": [{"id", "x"}, ...] of a body of `dim` dimensions.
NodeTable ReadNodes(const JsonNode& nodes, int dim);

// "x", "y" or "z" (in 3-D) as a coordinate index.
int ParseDirection(const JsonNode& d, int dim);

}  // namespace cb::io::reading
