// The readings of the arch trusses of P2 and P3 (docs/problems.md, "Other readings"): every
// topology, placement and area rule builds a stable, mirror-symmetric truss whose counts follow
// the closed forms of its topology, and the default reading is the construction the report's
// counts were checked on, unchanged.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "model/truss.h"
#include "problems/problem.h"

namespace cb {
namespace {

const Truss& TrussOf(const Problem& p) { return dynamic_cast<const Truss&>(p.body->body()); }

struct Counts {
  int nodes, members, lower_nodes;
};

// With P = upper_nodes - 1 panels. warren: P + 2 lower nodes; P upper chords, P + 1 lower
// chords, 2 P diagonals, 2 end posts. The aligned topologies: P + 1 lower nodes; P + P chords,
// P + 1 verticals, and one diagonal per panel (two in the centre panel when P is odd) or two
// (x-braced).
Counts ClosedFormCounts(const std::string& topology, int upper_nodes) {
  const int panels = upper_nodes - 1;
  if (topology == "warren") return {2 * panels + 3, 4 * panels + 3, panels + 2};
  const int diagonals = topology == "x-braced" ? 2 * panels : panels + panels % 2;
  return {2 * panels + 2, 3 * panels + 1 + diagonals, panels + 1};
}

const char* const kTopologies[] = {"warren", "pratt", "howe", "x-braced"};
const char* const kPlacements[] = {"radial", "vertical"};
const char* const kAreaGroups[] = {"from-supports", "from-centre", "uniform", "by-member-type"};

TEST(ArchReadingsTest, EveryReadingHasItsTopologysCounts) {
  for (const char* problem : {"arch-flat", "arch-curved"}) {
    const int upper_nodes = std::string(problem) == "arch-flat" ? 30 : 70;
    for (const char* topology : kTopologies) {
      for (const char* placement : kPlacements) {
        for (const char* groups : kAreaGroups) {
          const Problem p = MakeProblem(
              problem,
              {{"topology", topology}, {"lower_placement", placement}, {"area_groups", groups}});
          const Counts c = ClosedFormCounts(topology, upper_nodes);
          const std::string what =
              std::string(problem) + " " + topology + " " + placement + " " + groups;
          EXPECT_EQ(p.body->body().num_nodes(), c.nodes) << what;
          EXPECT_EQ(static_cast<int>(TrussOf(p).members().size()), c.members) << what;
          EXPECT_EQ(p.model->num_dofs(), 2 * c.nodes - 3) << what;  // (a) roller, (b) pinned
          EXPECT_EQ(p.model->num_pairs(), (upper_nodes - 2) + 2 * c.lower_nodes) << what;
        }
      }
    }
  }
}

TEST(ArchReadingsTest, TheReportsCountsComeOnlyFromWarren) {
  // P2: d = 119, nc = 90 as the report states; the aligned readings have one lower node fewer.
  EXPECT_EQ(MakeProblem("arch-flat").model->num_dofs(), 119);
  const Problem pratt = MakeProblem("arch-flat", {{"topology", "pratt"}});
  EXPECT_EQ(pratt.model->num_dofs(), 117);
  EXPECT_EQ(pratt.model->num_pairs(), 88);
  EXPECT_EQ(TrussOf(pratt).members().size(), 118u);  // 29 panels: both diagonals at the centre
  // P3 has 69 panels too: an odd number, so the same rule.
  EXPECT_EQ(TrussOf(MakeProblem("arch-curved", {{"topology", "howe"}})).members().size(), 278u);
}

// The stiffness at the unloaded state is positive definite: no reading has a mechanism.
bool StiffnessIsPositiveDefinite(const Problem& p) {
  SpMat k;
  p.body->body().Stiffness(Vec::Zero(p.model->num_dofs()), &k);
  Eigen::SimplicialLLT<SpMat> llt(k);
  return llt.info() == Eigen::Success;
}

// Every member has a mirror image (x -> -x) of the same area, so the symmetric path of the
// report exists in every reading.
bool IsMirrorSymmetric(const Truss& t) {
  auto mirror_node = [&](int n) {
    const Point x = t.reference(n);
    for (int m = 0; m < t.num_nodes(); ++m) {
      const Point y = t.reference(m);
      if (std::abs(y[0] + x[0]) < 1e-9 && std::abs(y[1] - x[1]) < 1e-9) return m;
    }
    return -1;
  };
  std::set<std::tuple<int, int, double>> members;
  for (const auto& m : t.members()) {
    members.insert({std::min(m.node_i, m.node_j), std::max(m.node_i, m.node_j), m.area});
  }
  for (const auto& m : t.members()) {
    const int i = mirror_node(m.node_i), j = mirror_node(m.node_j);
    if (i < 0 || j < 0 || !members.count({std::min(i, j), std::max(i, j), m.area})) return false;
  }
  return true;
}

TEST(ArchReadingsTest, EveryReadingIsStableAndSymmetric) {
  for (const char* topology : kTopologies) {
    for (const char* placement : kPlacements) {
      for (const char* groups : kAreaGroups) {
        const Problem p = MakeProblem("arch-flat", {{"topology", topology},
                                                    {"lower_placement", placement},
                                                    {"area_groups", groups},
                                                    {"centre_area", "0.045"}});
        const std::string what = std::string(topology) + " " + placement + " " + groups;
        EXPECT_TRUE(StiffnessIsPositiveDefinite(p)) << what;
        EXPECT_TRUE(IsMirrorSymmetric(TrussOf(p))) << what;
      }
    }
  }
}

// The angle of a node about the common centre of the two layers, (0, R cos omega) of P2.
double AngleAboutCentre(const Point& x) {
  const double omega = 20.0 * std::numbers::pi / 180.0;
  return std::atan2(x[0], 7.5 / std::tan(omega) - x[1]);
}

TEST(ArchReadingsTest, PrattFallsTowardsTheCentreAndHoweRises) {
  // Off the centre panel a Pratt diagonal joins the upper node nearer the support to the lower
  // node nearer the centre; a Howe diagonal the other way round.
  for (const char* topology : {"pratt", "howe"}) {
    const Problem p = MakeProblem("arch-flat", {{"topology", topology}});
    const Truss& t = TrussOf(p);
    int checked = 0;
    for (const auto& m : t.members()) {
      const Point a = t.reference(m.node_i), b = t.reference(m.node_j);
      const double angle_a = AngleAboutCentre(a), angle_b = AngleAboutCentre(b);
      const bool chord = std::abs(a[1] - b[1]) < 0.5 && std::abs(angle_a - angle_b) > 1e-9;
      const bool vertical = std::abs(angle_a - angle_b) < 1e-9;
      if (chord || vertical || angle_a * angle_b <= 0.0) continue;  // or the centre panel
      const bool a_upper = a[1] > b[1];
      const double upper = std::abs(a_upper ? angle_a : angle_b);
      const double lower = std::abs(a_upper ? angle_b : angle_a);
      EXPECT_EQ(upper > lower, std::string(topology) == "pratt") << topology;
      ++checked;
    }
    EXPECT_EQ(checked, 28) << topology;  // 29 panels less the centre one
  }
}

double H1(const Problem& p) {
  double lowest = 0.0;
  for (int n = 0; n < p.body->body().num_nodes(); ++n) {
    lowest = std::min(lowest, p.body->body().reference(n)[1]);
  }
  return -lowest;
}

TEST(ArchReadingsTest, VerticalPlacementKeepsH1AndHangsUnderTheUpperCircle) {
  const Problem p = MakeProblem("arch-flat", {{"lower_placement", "vertical"}});
  EXPECT_NEAR(H1(p), 2.3225, 5e-5);
  // Every lower node is layer_gap below the upper circle at its own x.
  const double radius = 7.5 / std::sin(20.0 * std::numbers::pi / 180.0);
  const double centre_y = radius * std::cos(20.0 * std::numbers::pi / 180.0);
  const ElasticBody& body = p.body->body();
  for (int n = 30; n < body.num_nodes(); ++n) {
    const double x = body.reference(n)[0];
    EXPECT_NEAR(body.reference(n)[1], centre_y - std::sqrt(radius * radius - x * x) - 1.0, 1e-12);
  }
  // With 29 panels the aligned topologies have no lower centre node: their lowest nodes lie half
  // a panel off the centre, (R + 1) cos(panel / 2) - R cos(omega) deep, 1.7 mm above H1.
  const double omega = 20.0 * std::numbers::pi / 180.0;
  const double half_panel = omega / 29.0;
  EXPECT_NEAR(H1(MakeProblem("arch-flat", {{"topology", "x-braced"}})),
              (radius + 1.0) * std::cos(half_panel) - radius * std::cos(omega), 1e-12);
}

std::multiset<double> Areas(const Problem& p) {
  std::multiset<double> areas;
  for (const auto& m : TrussOf(p).members()) areas.insert(m.area);
  return areas;
}

TEST(ArchReadingsTest, AreaRules) {
  // from-centre numbers the same 15 groups the other way: the same areas, reversed in space.
  const Problem centre = MakeProblem("arch-flat", {{"area_groups", "from-centre"}});
  const Truss& t = TrussOf(centre);
  EXPECT_NEAR(t.members().back().area, 0.05, 1e-12);  // an end post: the outermost group
  EXPECT_NEAR(t.members()[14].area, 0.33, 1e-12);     // the centre panel's upper chord
  const Problem uniform = MakeProblem("arch-flat", {{"area_groups", "uniform"}});
  for (const auto& m : TrussOf(uniform).members()) EXPECT_EQ(m.area, 0.33);
  // by-member-type: 29 upper chords, 30 lower chords, 58 diagonals, 2 posts.
  const std::multiset<double> by_type =
      Areas(MakeProblem("arch-flat", {{"area_groups", "by-member-type"}}));
  EXPECT_EQ(by_type.count(0.33), 29u);
  EXPECT_EQ(by_type.count(0.33 - 0.02), 30u);
  EXPECT_EQ(by_type.count(0.33 - 2 * 0.02), 58u);
  EXPECT_EQ(by_type.count(0.33 - 3 * 0.02), 2u);
  // centre_area replaces the centre group of warren: the centre panel's upper chord, its two
  // diagonals and the two lower chords meeting at the centre node.
  const std::multiset<double> thinned = Areas(MakeProblem("arch-flat", {{"centre_area", "0.045"}}));
  EXPECT_EQ(thinned.count(0.045), 5u);
  EXPECT_EQ(Areas(MakeProblem("arch-flat")).count(0.33 - 14 * 0.02), 5u);
  EXPECT_THROW(MakeProblem("arch-flat", {{"area_step", "0.03"}}), std::invalid_argument);
  EXPECT_THROW(MakeProblem("arch-flat", {{"topology", "k-truss"}}), std::invalid_argument);
  EXPECT_THROW(MakeProblem("arch-flat", {{"centre_area", "-1"}}), std::invalid_argument);
}

// The construction of P2 and P3 as it was before the readings became parameters, written out
// here independently: the default reading must build exactly this.
struct Reference {
  Mat xy;
  std::vector<std::tuple<int, int, double>> members;
};

Reference ConstructionBeforeReadings(double half_span, double half_angle_deg, int n_upper,
                                     double area_first) {
  const double omega = half_angle_deg * std::numbers::pi / 180.0;
  const double radius = half_span / std::sin(omega);
  const int panels = n_upper - 1;
  const double panel_angle = 2.0 * omega / panels;
  const double centre_y = radius * std::cos(omega);
  const int n_lower = panels + 2;
  Reference r;
  r.xy.resize(n_upper + n_lower, 2);
  auto place = [&](int node, double angle, double rad) {
    r.xy.row(node) << rad * std::sin(angle), centre_y - rad * std::cos(angle);
  };
  for (int i = 0; i < n_upper; ++i) place(i, -omega + i * panel_angle, radius);
  const int lower0 = n_upper;
  place(lower0, -omega, radius + 1.0);
  for (int k = 0; k < panels; ++k) {
    place(lower0 + 1 + k, -omega + (k + 0.5) * panel_angle, radius + 1.0);
  }
  place(lower0 + n_lower - 1, omega, radius + 1.0);
  std::vector<std::pair<int, int>> links;
  for (int i = 0; i + 1 < n_upper; ++i) links.emplace_back(i, i + 1);
  for (int k = 0; k + 1 < n_lower; ++k) links.emplace_back(lower0 + k, lower0 + k + 1);
  for (int k = 0; k < panels; ++k) {
    links.emplace_back(lower0 + 1 + k, k);
    links.emplace_back(lower0 + 1 + k, k + 1);
  }
  links.emplace_back(lower0, 0);
  links.emplace_back(lower0 + n_lower - 1, n_upper - 1);
  for (const auto& [i, j] : links) {
    const double mx = 0.5 * (r.xy(i, 0) + r.xy(j, 0));
    const double my = 0.5 * (r.xy(i, 1) + r.xy(j, 1));
    const double distance = omega - std::abs(std::atan2(mx, centre_y - my));
    const int group = 1 + static_cast<int>(std::floor(distance / panel_angle + 1e-9));
    r.members.emplace_back(i, j, area_first - (group - 1) * 0.02);
  }
  return r;
}

void ExpectSameTruss(const Truss& t, const Reference& r, const std::string& what) {
  ASSERT_EQ(t.num_nodes(), r.xy.rows()) << what;
  for (int n = 0; n < t.num_nodes(); ++n) {
    EXPECT_EQ(t.reference(n)[0], r.xy(n, 0)) << what << " node " << n;  // bit for bit
    EXPECT_EQ(t.reference(n)[1], r.xy(n, 1)) << what << " node " << n;
  }
  ASSERT_EQ(t.members().size(), r.members.size()) << what;
  for (std::size_t m = 0; m < r.members.size(); ++m) {
    EXPECT_EQ(t.members()[m].node_i, std::get<0>(r.members[m])) << what << " member " << m;
    EXPECT_EQ(t.members()[m].node_j, std::get<1>(r.members[m])) << what << " member " << m;
    EXPECT_EQ(t.members()[m].area, std::get<2>(r.members[m])) << what << " member " << m;
  }
}

TEST(ArchReadingsTest, DefaultReadingIsTheConstructionBefore) {
  const std::map<std::string, std::string> explicit_default = {{"topology", "warren"},
                                                               {"area_groups", "from-supports"},
                                                               {"centre_area", "0"},
                                                               {"lower_placement", "radial"}};
  const Reference p2 = ConstructionBeforeReadings(7.5, 20.0, 30, 0.33);
  ExpectSameTruss(TrussOf(MakeProblem("arch-flat")), p2, "arch-flat");
  ExpectSameTruss(TrussOf(MakeProblem("arch-flat", explicit_default)), p2, "arch-flat explicit");
  const Reference p3 = ConstructionBeforeReadings(37.5, 5.0, 70, 0.73);
  ExpectSameTruss(TrussOf(MakeProblem("arch-curved")), p3, "arch-curved");
  ExpectSameTruss(TrussOf(MakeProblem("arch-curved", explicit_default)), p3,
                  "arch-curved explicit");
}

}  // namespace
}  // namespace cb
