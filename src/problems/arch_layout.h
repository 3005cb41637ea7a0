// The nodes and members of the two-layer arch truss of P2 and P3 (docs/problems.md): where the
// lower nodes sit and which members join the two layers. The report's figure is not legible
// enough to read these, so each reading is a choice (parameters `topology`, `lower_placement`).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/types.h"

namespace cb {

// warren: a lower node at the mid-angle of every panel plus the two end nodes, two diagonals
// from each mid-panel node (the default: d = 119, nc = 90 as the report states). pratt, howe,
// x-braced: a lower node under every upper node, a vertical at each, and per panel one diagonal
// falling towards the centre (pratt), rising towards it (howe) or both (x-braced). With an odd
// number of panels the centre panel of pratt and howe has both diagonals, to stay symmetric.
enum class ArchTopology { kWarren, kPratt, kHowe, kXBraced };
// radial: the lower layer on the circle of radius R + layer_gap about the common centre.
// vertical: each lower node layer_gap straight below the point of the upper circle at its angle.
// Both put the lower centre node at the depth H1 = R (1 - cos omega) + layer_gap.
enum class LowerPlacement { kRadial, kVertical };
enum class MemberType { kUpperChord, kLowerChord, kDiagonal, kPost };

// Names as the parameters spell them, in the order of the enumerations.
const std::vector<std::string>& ArchTopologyNames();
const std::vector<std::string>& LowerPlacementNames();
ArchTopology ArchTopologyNamed(const std::string& name);
LowerPlacement LowerPlacementNamed(const std::string& name);

// The circular geometry: both layers about one centre at (0, centre_y) above the truss.
struct ArchCircle {
  double omega = 0.0;   // half opening angle [rad]
  double radius = 0.0;  // R of the upper layer
  double layer_gap = 0.0;
  double centre_y = 0.0;  // R cos(omega): the ends of the upper layer at y = 0
  int upper_nodes = 0;
  double panel_angle() const { return 2.0 * omega / (upper_nodes - 1); }
};

struct ArchLayout {
  Mat xy;               // upper nodes 0 .. upper_nodes-1 (left to right), then the lower layer
  int first_lower = 0;  // index of the leftmost lower node
  int lower_nodes = 0;
  std::vector<std::pair<int, int>> links;  // members' end nodes
  std::vector<MemberType> types;           // one per link
};

ArchLayout LayOutArch(const ArchCircle& circle, ArchTopology topology, LowerPlacement placement);

}  // namespace cb
