#include "problems/arch_layout.h"

#include <cmath>
#include <stdexcept>

namespace cb {

namespace {

template <typename Enum>
Enum Named(const std::vector<std::string>& names, const std::string& name, const char* what) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<Enum>(i);
  }
  throw std::invalid_argument(std::string(what) + ": unknown reading '" + name + "'");
}

// The angles of the lower nodes: the end nodes and the mid-angle of every panel (warren), or
// the angles of the upper nodes (the aligned topologies).
std::vector<double> LowerAngles(const ArchCircle& c, ArchTopology topology) {
  const int panels = c.upper_nodes - 1;
  const double panel_angle = c.panel_angle();
  std::vector<double> angles;
  if (topology == ArchTopology::kWarren) {
    angles.push_back(-c.omega);
    for (int k = 0; k < panels; ++k) angles.push_back(-c.omega + (k + 0.5) * panel_angle);
    angles.push_back(c.omega);
  } else {
    for (int i = 0; i < c.upper_nodes; ++i) angles.push_back(-c.omega + i * panel_angle);
  }
  return angles;
}

struct Links {
  std::vector<std::pair<int, int>> links;
  std::vector<MemberType> types;
  void Add(int i, int j, MemberType type) {
    links.emplace_back(i, j);
    types.push_back(type);
  }
};

// Two diagonals from each mid-panel lower node to the upper nodes of its panel, and the two end
// posts.
void AddWarrenWeb(int upper_nodes, int first_lower, Links* out) {
  const int panels = upper_nodes - 1;
  for (int k = 0; k < panels; ++k) {
    out->Add(first_lower + 1 + k, k, MemberType::kDiagonal);
    out->Add(first_lower + 1 + k, k + 1, MemberType::kDiagonal);
  }
  out->Add(first_lower, 0, MemberType::kPost);
  out->Add(first_lower + panels + 1, upper_nodes - 1, MemberType::kPost);
}

// A vertical under every upper node, then the diagonals panel by panel. In panel k the upper
// nodes are k, k + 1 and the lower nodes first_lower + k, + k + 1; its outer end is the one
// nearer its support.
void AddAlignedWeb(ArchTopology topology, int upper_nodes, int first_lower, Links* out) {
  const int panels = upper_nodes - 1;
  for (int i = 0; i < upper_nodes; ++i) out->Add(first_lower + i, i, MemberType::kPost);
  for (int k = 0; k < panels; ++k) {
    const bool left_half = 2 * k + 1 < panels;
    const bool centre_panel = 2 * k + 1 == panels;
    const int upper_outer = left_half ? k : k + 1;
    const int upper_inner = left_half ? k + 1 : k;
    const int lower_outer = first_lower + (left_half ? k : k + 1);
    const int lower_inner = first_lower + (left_half ? k + 1 : k);
    const bool both = topology == ArchTopology::kXBraced || centre_panel;
    // Falling towards the centre (Pratt), rising towards it (Howe).
    if (both || topology == ArchTopology::kPratt) {
      out->Add(upper_outer, lower_inner, MemberType::kDiagonal);
    }
    if (both || topology == ArchTopology::kHowe) {
      out->Add(lower_outer, upper_inner, MemberType::kDiagonal);
    }
  }
}

}  // namespace

const std::vector<std::string>& ArchTopologyNames() {
  static const std::vector<std::string> names = {"warren", "pratt", "howe", "x-braced"};
  return names;
}

const std::vector<std::string>& LowerPlacementNames() {
  static const std::vector<std::string> names = {"radial", "vertical"};
  return names;
}

ArchTopology ArchTopologyNamed(const std::string& name) {
  return Named<ArchTopology>(ArchTopologyNames(), name, "topology");
}

LowerPlacement LowerPlacementNamed(const std::string& name) {
  return Named<LowerPlacement>(LowerPlacementNames(), name, "lower_placement");
}

ArchLayout LayOutArch(const ArchCircle& c, ArchTopology topology, LowerPlacement placement) {
  const std::vector<double> lower_angles = LowerAngles(c, topology);
  ArchLayout layout;
  layout.first_lower = c.upper_nodes;
  layout.lower_nodes = static_cast<int>(lower_angles.size());
  layout.xy.resize(c.upper_nodes + layout.lower_nodes, 2);
  auto place = [&](int node, double angle, double r) {
    layout.xy.row(node) << r * std::sin(angle), c.centre_y - r * std::cos(angle);
  };
  for (int i = 0; i < c.upper_nodes; ++i) place(i, -c.omega + i * c.panel_angle(), c.radius);
  for (int k = 0; k < layout.lower_nodes; ++k) {
    const int node = layout.first_lower + k;
    if (placement == LowerPlacement::kRadial) {
      place(node, lower_angles[k], c.radius + c.layer_gap);
    } else {
      place(node, lower_angles[k], c.radius);
      layout.xy(node, 1) -= c.layer_gap;
    }
  }

  Links links;
  for (int i = 0; i + 1 < c.upper_nodes; ++i) links.Add(i, i + 1, MemberType::kUpperChord);
  for (int k = 0; k + 1 < layout.lower_nodes; ++k) {
    links.Add(layout.first_lower + k, layout.first_lower + k + 1, MemberType::kLowerChord);
  }
  if (topology == ArchTopology::kWarren) {
    AddWarrenWeb(c.upper_nodes, layout.first_lower, &links);
  } else {
    AddAlignedWeb(topology, c.upper_nodes, layout.first_lower, &links);
  }
  layout.links = std::move(links.links);
  layout.types = std::move(links.types);
  return layout;
}

}  // namespace cb
