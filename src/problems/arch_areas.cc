#include "problems/arch_areas.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cb {

namespace {

// 1 + floor(angular distance of the member's midpoint from the nearer end / panel angle).
// Members whose midpoint lies on a panel boundary (the lower chord of warren, the verticals)
// sit exactly on an integer; the small relative tolerance makes that integer win over rounding.
int GroupFromSupports(const ArchLayout& layout, const ArchCircle& c, int i, int j) {
  const double mx = 0.5 * (layout.xy(i, 0) + layout.xy(j, 0));
  const double my = 0.5 * (layout.xy(i, 1) + layout.xy(j, 1));
  const double angle = std::atan2(mx, c.centre_y - my);
  const double distance = c.omega - std::abs(angle);
  return 1 + static_cast<int>(std::floor(distance / c.panel_angle() + 1e-9));
}

int TypeGroup(MemberType type) {
  switch (type) {
    case MemberType::kUpperChord:
      return 1;
    case MemberType::kLowerChord:
      return 2;
    case MemberType::kDiagonal:
      return 3;
    case MemberType::kPost:
      return 4;
  }
  return 4;
}

}  // namespace

const std::vector<std::string>& AreaGroupsNames() {
  static const std::vector<std::string> names = {"from-supports", "from-centre", "uniform",
                                                 "by-member-type"};
  return names;
}

AreaGroups AreaGroupsNamed(const std::string& name) {
  const auto& names = AreaGroupsNames();
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) throw std::invalid_argument("area_groups: unknown rule '" + name + "'");
  return static_cast<AreaGroups>(found - names.begin());
}

std::vector<double> MemberAreas(const ArchLayout& layout, const ArchCircle& circle,
                                const AreaRule& rule) {
  std::vector<int> from_supports;
  for (const auto& [i, j] : layout.links) {
    from_supports.push_back(GroupFromSupports(layout, circle, i, j));
  }
  const int centre_group = *std::max_element(from_supports.begin(), from_supports.end());
  std::vector<double> areas;
  for (std::size_t m = 0; m < layout.links.size(); ++m) {
    int group = from_supports[m];
    if (rule.groups == AreaGroups::kFromCentre) group = centre_group + 1 - group;
    if (rule.groups == AreaGroups::kUniform) group = 1;
    if (rule.groups == AreaGroups::kByMemberType) group = TypeGroup(layout.types[m]);
    double area = rule.first - (group - 1) * rule.step;
    if (rule.centre_area > 0.0 && from_supports[m] == centre_group) area = rule.centre_area;
    if (!(area > 0.0)) {
      throw std::invalid_argument(
          "area_first - (group - 1) * area_step is not positive for group " +
          std::to_string(group));
    }
    areas.push_back(area);
  }
  return areas;
}

}  // namespace cb
