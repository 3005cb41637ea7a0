// The cross-section areas of the arch truss's members (docs/problems.md, P2): the report prints
// "(1), (2), (3), ... = 0.33, 0.31, 0.29, ..." and its figure does not show which members form
// a group, so the group rule is a choice (parameters `area_groups`, `centre_area`).
#pragma once

#include <string>
#include <vector>

#include "problems/arch_layout.h"

namespace cb {

// from-supports: groups are panels counted from the nearer support (the default);
// from-centre: the same panels counted from the centre; uniform: one group; by-member-type:
// (1) upper chord, (2) lower chord, (3) diagonals, (4) posts and verticals.
enum class AreaGroups { kFromSupports, kFromCentre, kUniform, kByMemberType };

const std::vector<std::string>& AreaGroupsNames();
AreaGroups AreaGroupsNamed(const std::string& name);

struct AreaRule {
  AreaGroups groups = AreaGroups::kFromSupports;
  double first = 0.0;  // area of group 1
  double step = 0.0;   // decrease per group
  // When positive, the area of the centre members (those of the largest group counted from the
  // supports), whatever the rule gives them.
  double centre_area = 0.0;
};

// One area per link of `layout`. Throws std::invalid_argument when a group's area is not
// positive.
std::vector<double> MemberAreas(const ArchLayout& layout, const ArchCircle& circle,
                                const AreaRule& rule);

}  // namespace cb
