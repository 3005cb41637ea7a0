#include "harness/vtk_pieces.h"

#include <algorithm>
#include <climits>
#include <stdexcept>

namespace cb::harness {

BodyPiece PieceOfProcess(const ElasticBody& body, const std::vector<std::vector<int>>& parts,
                         int process, int processes) {
  if (process < 0 || process >= processes) {
    throw std::invalid_argument("process " + std::to_string(process) + " of " +
                                std::to_string(processes));
  }
  const std::vector<std::vector<int>> cells = body.Cells();
  std::vector<std::vector<int>> owned(static_cast<std::size_t>(processes));
  if (parts.empty()) {
    for (std::size_t c = 0; c < cells.size(); ++c) owned[0].push_back(static_cast<int>(c));
  } else if (parts.size() == owned.size()) {
    owned = parts;
  } else {
    throw std::invalid_argument("parts: " + std::to_string(parts.size()) + " lists for " +
                                std::to_string(processes) + " processes");
  }
  // The owner of a node: the lowest process whose elements use it; process 0 for a node of none.
  std::vector<int> owner(static_cast<std::size_t>(body.num_nodes()), INT_MAX);
  std::vector<bool> in_piece(owner.size(), false);
  for (int p = 0; p < processes; ++p) {
    for (int c : owned[static_cast<std::size_t>(p)]) {
      for (int node : cells.at(static_cast<std::size_t>(c))) {
        owner[node] = std::min(owner[node], p);
        if (p == process) in_piece[node] = true;
      }
    }
  }
  BodyPiece piece;
  piece.cells = owned[static_cast<std::size_t>(process)];
  for (int node = 0; node < body.num_nodes(); ++node) {
    if (owner[node] == INT_MAX) owner[node] = 0;  // a node of no element
    if (!in_piece[node] && !(owner[node] == 0 && process == 0)) continue;
    piece.nodes.push_back(node);
    piece.duplicate.push_back(owner[node] != process);
  }
  return piece;
}

std::string PieceFile(const std::string& stem, int process) {
  return stem + "_p" + std::to_string(process) + ".vtu";
}

}  // namespace cb::harness
