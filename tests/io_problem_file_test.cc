// Problem files (src/io/): every registry problem written and read back gives the same model;
// the examples load with the counts they state; every class of bad input is refused with a
// message naming the file, the JSON pointer (or mesh line/element) and the reason.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "fixtures.h"
#include "formulations/registry.h"
#include "io/gmsh.h"
#include "io/input_error.h"
#include "io/json_node.h"
#include "io/problem_file.h"
#include "path/path.h"
#include "refusal.h"
#include "source_tree.h"

namespace cb {
namespace {

using nlohmann::json;

const std::filesystem::path kExamples = ::cb::testing_support::SourceRoot() / "examples";

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_io_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

Vec RandomVector(int n, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return Vec::NullaryExpr(n, [&] { return scale * unit(rng); });
}

// The two models agree on every evaluation at u (to rounding).
void ExpectSameModel(const ContactModel& a, const ContactModel& b, const Vec& u,
                     const std::string& what) {
  ASSERT_EQ(a.num_dofs(), b.num_dofs()) << what;
  ASSERT_EQ(a.num_pairs(), b.num_pairs()) << what;
  EXPECT_EQ(a.is_linear(), b.is_linear()) << what;
  EXPECT_EQ(a.has_energy(), b.has_energy()) << what;
  if (a.has_energy()) {
    EXPECT_NEAR(a.Energy(u), b.Energy(u), 1e-12 * std::max(1.0, std::abs(a.Energy(u)))) << what;
  }
  Vec fa, fb, pa, pb;
  a.InternalForce(u, &fa);
  b.InternalForce(u, &fb);
  EXPECT_TRUE(fixtures::RelativelyClose(fb, fa, 1e-12, 1e-12, what + " internal force"));
  a.Gaps(u, &pa);
  b.Gaps(u, &pb);
  EXPECT_TRUE(fixtures::RelativelyClose(pb, pa, 1e-12, 1e-12, what + " gaps"));
  SpMat ka, kb, ga, gb;
  a.Stiffness(u, &ka);
  b.Stiffness(u, &kb);
  EXPECT_LE(Mat(ka - kb).lpNorm<Eigen::Infinity>(), 1e-12 * Mat(ka).lpNorm<Eigen::Infinity>())
      << what << " stiffness";
  a.GapJacobian(u, &ga);
  b.GapJacobian(u, &gb);
  EXPECT_LE(Mat(ga - gb).lpNorm<Eigen::Infinity>(), 1e-12) << what << " gap Jacobian";
  // Exact, not close: the load pattern is written and read digit for digit.
  EXPECT_EQ(a.load_pattern(), b.load_pattern()) << what << " load pattern";
}

TEST(IoProblemFileTest, EveryRegistryProblemRoundTrips) {
  for (const auto& name : ProblemNames()) {
    // block with n = 6 and hertz-3d on 3 x 3 x 2: the same code as the defaults, faster (the
    // comparison forms dense matrices).
    const Problem p = name == "block"      ? MakeProblem(name, {{"n", "6"}})
                      : name == "hertz-3d" ? MakeProblem(name, {{"n", "3"}, {"nz", "2"}})
                                           : MakeProblem(name);
    const std::string text = io::ProblemToJson(p);
    const Problem q = io::ParseProblemFile(text, name + ".json", ".");
    EXPECT_EQ(q.name, p.name);
    EXPECT_EQ(q.description, p.description);
    EXPECT_EQ(q.units, p.units);
    EXPECT_EQ(q.scales.length, p.scales.length) << name;
    EXPECT_EQ(q.scales.force, p.scales.force) << name;
    EXPECT_EQ(q.loading, p.loading) << name;
    if (p.loading == LoadingKind::kFixedLoad) {
      EXPECT_EQ(q.load, p.load) << name;
    } else {
      EXPECT_EQ(q.arc_length, p.arc_length) << name;
      EXPECT_EQ(q.steps, p.steps) << name;
    }
    EXPECT_EQ(q.control_dof, p.control_dof) << name;
    EXPECT_EQ(q.control_label, p.control_label) << name;
    ASSERT_NE(q.body, nullptr) << name;
    EXPECT_EQ(q.body->body().num_nodes(), p.body->body().num_nodes()) << name;
    // Displacements of a few per cent of the smallest gap scale: large enough for the
    // geometric nonlinearity of the trusses and the curved obstacle to show.
    for (unsigned seed : {1u, 2u}) {
      const Vec u = RandomVector(p.model->num_dofs(), p.scales.length, seed);
      ExpectSameModel(*p.model, *q.model, u, name);
    }
    // Written again, the file is the same (but for its provenance, which now lists the run
    // parameters of a file instead of the builder's): nothing is lost or reordered.
    json again = json::parse(io::ProblemToJson(q));
    json first = json::parse(text);
    again.erase("source");
    first.erase("source");
    EXPECT_EQ(again, first) << name;
  }
}

TEST(IoProblemFileTest, LcpRoundTrips) {
  const Problem p = fixtures::ComplementarityProblem("lcp4", fixtures::Lcp4Model());
  const Problem q = io::ParseProblemFile(io::ProblemToJson(p), "lcp4.json", ".");
  EXPECT_EQ(q.body, nullptr);
  EXPECT_EQ(q.loading, LoadingKind::kFixedLoad);
  EXPECT_EQ(q.load, 0.0);
  ExpectSameModel(*p.model, *q.model, RandomVector(4, 1.0, 3), "lcp4");
}

// An LCP whose solution is ~1e-4: by default its scales are the sizes the data imply
// (R = ||q||_inf, L = R / ||M||_inf), so every formulation solves an O(1) problem and answers
// to relative accuracy. With L = R = 1 Ipopt stopped ~1e-5 relative from the answer.
TEST(IoProblemFileTest, AnLcpsDefaultScalesComeFromItsData) {
  const std::string text =
      R"({"kind": "lcp", "M": [[2, 1, 0], [1, 2, 1], [0, 1, 2]], "q": [-2e-4, 3e-4, -3e-4]})";
  const Problem p = io::ParseProblemFile(text, "small.json", ".");
  EXPECT_DOUBLE_EQ(p.scales.force, 3e-4);
  EXPECT_DOUBLE_EQ(p.scales.length, 3e-4 / 4.0);  // ||M||_inf = 4
  const Problem given = io::ParseProblemFile(
      R"({"kind": "lcp", "M": [[2]], "q": [-1], "length_scale": 5, "force_scale": 7})", "g.json",
      ".");
  EXPECT_EQ(given.scales.length, 5.0);
  EXPECT_EQ(given.scales.force, 7.0);

  Vec exact(3);
  exact << 1e-4, 0.0, 1.5e-4;  // z2 = 0: 2 z1 = 2e-4, 2 z3 = 3e-4; w2 = z1 + z3 + 3e-4 > 0
  const StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(0.0),
                         p.scales};
  for (const FormulationInfo& info : FormulationRegistry()) {
    if (!info.available) continue;
    const auto formulation = MakeFormulation(info.name, FormulationConfig());
    if (!formulation->Accepts(step, nullptr)) continue;
    StartPoint start;  // as `run` starts a fixed-load step: from z = 0, r = 0
    start.du = Vec::Zero(3);
    start.r = Vec::Zero(3);
    const StepResult result = formulation->Solve(step, start);
    const Verdict verdict = Judge(step, result.point, 1e-8);
    const double error = (result.point.du - exact).lpNorm<Eigen::Infinity>();
    // The verdict is relative to R, so it judges the answer as if the data were O(1): a
    // verified answer is accurate in relative terms.
    if (verdict.verified) {
      EXPECT_LE(error, 1e-6 * 1.5e-4) << info.name;
    }
    // nlopt-energy stops on its own xtol in the data's units, which no scale reaches: its
    // answer is ~6e-6 relative off and the verdict says so (with an absolute eq_res it passed).
    if (info.name == "nlopt-energy") {
      EXPECT_FALSE(verdict.verified) << "eq_res " << verdict.eq_res << ", error " << error;
      continue;
    }
    EXPECT_TRUE(verdict.verified) << info.name << ": " << result.message;
  }
}

TEST(IoProblemFileTest, ExamplesLoadWithTheirStatedCounts) {
  struct Case {
    const char* file;
    int dofs;
    int pairs;
    LoadingKind loading;
  } cases[] = {
      {"truss-2d-bar-wall.json", 2, 1, LoadingKind::kArcLength},
      {"truss-3d-tripod.json", 3, 1, LoadingKind::kArcLength},
      {"q4-block-on-floor.json", 17, 3, LoadingKind::kFixedLoad},
      {"q4-block-gmsh.json", 11, 3, LoadingKind::kFixedLoad},
      // 1595 nodes less the 53 x components on the axis; the arc's 84 edges.
      {"hertz-2d.json", 2 * 1595 - 53, 85, LoadingKind::kFixedLoad},
      {"lcp-dense-2x2.json", 2, 2, LoadingKind::kFixedLoad},
      {"lcp-sparse-4x4.json", 4, 4, LoadingKind::kFixedLoad},
  };
  for (const auto& c : cases) {
    const Problem p = io::LoadProblemFile((kExamples / c.file).string());
    EXPECT_EQ(p.model->num_dofs(), c.dofs) << c.file;
    EXPECT_EQ(p.model->num_pairs(), c.pairs) << c.file;
    EXPECT_EQ(p.loading, c.loading) << c.file;
  }
}

TEST(IoProblemFileTest, GmshAndInlineMeshesOfTheSameBlockCarryTheSameLoad) {
  // The Gmsh block has 2 elements, the inline one 4; the top traction integrates to the same
  // total: p * width * thickness = 10 * 2 * 0.1 = 2 (downward).
  for (const char* file : {"q4-block-on-floor.json", "q4-block-gmsh.json"}) {
    const Problem p = io::LoadProblemFile((kExamples / file).string());
    const Vec& f = p.model->load_pattern();
    double fy = 0.0;
    const ElasticBody& body = p.body->body();
    for (int n = 0; n < body.num_nodes(); ++n) {
      if (body.dofs().dof(n, 1) >= 0) fy += f[body.dofs().dof(n, 1)];
    }
    EXPECT_NEAR(fy, -2.0, 1e-12) << file;
  }
}

TEST(IoProblemFileTest, SettingsOverrideTheFilesRunParameters) {
  const Problem p = io::LoadProblemFile((kExamples / "truss-2d-bar-wall.json").string(),
                                        {{"steps", "7"}, {"length_scale", "0.5"}});
  EXPECT_EQ(p.steps, 7);
  EXPECT_EQ(p.scales.length, 0.5);
  EXPECT_THROW(
      io::LoadProblemFile((kExamples / "truss-2d-bar-wall.json").string(), {{"load", "2"}}),
      std::invalid_argument);  // an arc-length problem has no fixed load to set
}

TEST(IoProblemFileTest, LineColumnCountsFromOne) {
  EXPECT_EQ(io::LineColumn("ab\ncd", 1), "line 1, column 1");
  EXPECT_EQ(io::LineColumn("ab\ncd", 5), "line 2, column 2");
  EXPECT_EQ(io::LineColumn("ab\n", 4), "line 2, column 1");  // end of input
}

// --- bad inputs -----------------------------------------------------------------------------

const char* const kTruss = R"({
  "kind": "truss", "dimension": 2,
  "nodes": [{"id": 1, "x": [0, 0]}, {"id": 2, "x": [0.5, 0]}, {"id": 3, "x": [1, 0]}],
  "members": [{"nodes": [1, 2], "E": 100, "A": 1}, {"nodes": [2, 3], "E": 100, "A": 0.5}],
  "supports": [{"node": 1, "fixed": ["x", "y"]}, {"node": 2, "fixed": ["y"]},
               {"node": 3, "fixed": ["y"]}],
  "loads": [{"node": 3, "force": [1, 0]}],
  "obstacles": [{"id": "wall", "type": "half-space", "point": [1.01, 0], "normal": [1, 0]}],
  "contact_pairs": [{"node": 3, "obstacle": "wall"}],
  "length_scale": 0.01, "force_scale": 1,
  "analysis": "arc-length", "arc_length": 0.05, "steps": 10
})";

const char* const kQ4 = R"({
  "kind": "plane-stress-q4", "thickness": 0.1, "material": {"E": 1000, "nu": 0.25},
  "nodes": [{"id": 1, "x": [0, 0]}, {"id": 2, "x": [1, 0]}, {"id": 3, "x": [2, 0]},
            {"id": 4, "x": [0, 1]}, {"id": 5, "x": [1, 1]}, {"id": 6, "x": [2, 1]}],
  "elements": [{"nodes": [1, 2, 5, 4]}, {"nodes": [2, 3, 6, 5]}],
  "supports": [{"node": 1, "fixed": ["x"]}],
  "tractions": [{"edges": [[4, 5], [5, 6]], "traction": [0, -10]}],
  "obstacles": [{"id": "floor", "type": "half-space", "point": [0, 0], "normal": [0, -1]}],
  "contact_pairs": [{"node": 1, "obstacle": "floor"}, {"node": 2, "obstacle": "floor"},
                    {"node": 3, "obstacle": "floor"}],
  "length_scale": 0.01, "force_scale": 1, "analysis": "fixed-load"
})";

const char* const kLcp = R"({"kind": "lcp", "M": [[2, 1], [1, 2]], "q": [-5, -6]})";

struct BadCase {
  std::string name;
  const char* base;                   // a valid document, or nullptr: `text` is the file
  std::function<void(json&)> mutate;  // applied to the base
  std::string text;                   // the file's text when base is nullptr
  testing_support::Refusal expected;  // where the message points and what it names
};

std::vector<BadCase> BadCases() {
  return {
      {"malformed", nullptr, nullptr, "{\n  \"kind\": \"truss\",\n  \"nodes\": [1,, 2]\n}\n",
       testing_support::At("line 3, column 15")},
      {"overflow", nullptr, nullptr, R"({"kind": "lcp", "M": [[1e999]], "q": [1]})",
       testing_support::At("", {"1e999"})},
      {"overflow_pointer", nullptr, nullptr,
       R"({"kind": "lcp", "M": [[1, 2], [3, 1e400]], "q": [1, 2]})", testing_support::At("/M/1/1")},
      {"overflow_in_object", nullptr, nullptr,
       R"({"kind": "lcp", "scales": {"length": 1e400}, "M": [[1]], "q": [1]})",
       testing_support::At("/scales/length", {"'1e400'"})},
      {"not_an_object", nullptr, nullptr, "[1, 2]", testing_support::At("/")},
      {"missing_field", kTruss, [](json& j) { j.erase("members"); }, "",
       testing_support::At("/", {"'members'"})},
      {"unknown_field", kTruss, [](json& j) { j["memberz"] = 1; }, "",
       testing_support::At("/memberz")},
      {"unknown_nested_field", kTruss, [](json& j) { j["members"][1]["Ee"] = 1; }, "",
       testing_support::At("/members/1/Ee")},
      {"wrong_type", kTruss, [](json& j) { j["members"][0]["E"] = "100"; }, "",
       testing_support::At("/members/0/E")},
      {"unknown_kind", kTruss, [](json& j) { j["kind"] = "frame"; }, "",
       testing_support::At("/kind")},
      {"bad_version", kTruss, [](json& j) { j["version"] = 2; }, "",
       testing_support::At("/version")},
      {"bad_dimension", kTruss, [](json& j) { j["dimension"] = 4; }, "",
       testing_support::At("/dimension", {"4"})},
      {"short_vector", kTruss, [](json& j) { j["nodes"][0]["x"] = {0}; }, "",
       testing_support::At("/nodes/0/x", {"1"})},
      {"negative_E", kTruss, [](json& j) { j["members"][1]["E"] = -1; }, "",
       testing_support::At("/members/1/E", {"-1"})},
      {"zero_A", kTruss, [](json& j) { j["members"][0]["A"] = 0; }, "",
       testing_support::At("/members/0/A", {"0"})},
      {"zero_length_member", kTruss,
       [](json& j) {
         j["nodes"][1]["x"] = {0, 0};
       },
       "", testing_support::At("/nodes/1", {"/nodes/0", "node 2", "node 1"})},
      {"duplicated_node", kTruss,
       [](json& j) {
         j["nodes"].push_back({{"id", 9}, {"x", {0.5, 0}}});
       },
       "", testing_support::At("/nodes/3", {"/nodes/1", "node 9", "node 2"})},
      {"q4_edge_1e-300", kQ4,
       [](json& j) {
         j["nodes"][1]["x"] = {1e-300, 0};
       },
       "", testing_support::At("/nodes/1", {"node 2", "node 1"})},
      {"q4_degenerate_element", kQ4,
       [](json& j) {
         j["nodes"][1]["x"] = {1e-9, 0};
       },
       "", testing_support::At("/elements/0/nodes", {"side 0"})},
      {"member_to_itself", kTruss,
       [](json& j) {
         j["members"][0]["nodes"] = {1, 1};
       },
       "", testing_support::At("/members/0/nodes", {"node 1"})},
      {"duplicate_node_id", kTruss, [](json& j) { j["nodes"][2]["id"] = 1; }, "",
       testing_support::At("/nodes/2/id", {"/nodes/0", "1"})},
      {"unknown_node_id", kTruss, [](json& j) { j["members"][0]["nodes"][1] = 99; }, "",
       testing_support::At("/members/0/nodes/1", {"99"})},
      {"dangling_node", kTruss,
       [](json& j) {
         j["nodes"].push_back({{"id", 4}, {"x", {2, 0}}});
       },
       "", testing_support::At("/nodes/3", {"node 4"})},
      {"pair_unknown_node", kTruss, [](json& j) { j["contact_pairs"][0]["node"] = 42; }, "",
       testing_support::At("/contact_pairs/0/node", {"42"})},
      {"pair_unknown_obstacle", kTruss,
       [](json& j) { j["contact_pairs"][0]["obstacle"] = "floor"; }, "",
       testing_support::At("/contact_pairs/0/obstacle", {"\"floor\""})},
      {"duplicate_pair", kTruss,
       [](json& j) { j["contact_pairs"].push_back(j["contact_pairs"][0]); }, "",
       testing_support::At("/contact_pairs/1", {"\"wall\"", "node 3"})},
      {"pair_starts_inside", kTruss,
       [](json& j) {
         j["obstacles"][0]["point"] = {0.9, 0};
       },
       "", testing_support::At("/contact_pairs/0", {"\"wall\"", "node 3"})},
      {"zero_normal", kTruss,
       [](json& j) {
         j["obstacles"][0]["normal"] = {0, 0};
       },
       "", testing_support::At("/obstacles/0/normal")},
      {"bad_radius", kTruss,
       [](json& j) {
         j["obstacles"][0] = {{"id", "wall"}, {"type", "ball"}, {"centre", {3, 0}}, {"radius", -2}};
       },
       "", testing_support::At("/obstacles/0/radius", {"-2"})},
      {"nothing_holds", kTruss,
       [](json& j) {
         j.erase("supports");
         j.erase("contact_pairs");
       },
       "", testing_support::At("/")},
      {"supports_insufficient", kTruss,
       [](json& j) {
         j["supports"] = json::array({{{"node", 1}, {"fixed", {"x", "y"}}}});
         j.erase("contact_pairs");
       },
       "", testing_support::At("/supports")},
      {"pairs_insufficient", kTruss,
       [](json& j) {
         j["supports"] = json::array({{{"node", 2}, {"fixed", {"y"}}}});
       },
       "", testing_support::At("/supports")},
      {"unknown_direction", kTruss,
       [](json& j) {
         j["supports"][0]["fixed"] = {"x", "w"};
       },
       "", testing_support::At("/supports/0/fixed/1", {"\"w\""})},
      {"load_on_support", kTruss,
       [](json& j) {
         j["loads"][0]["force"] = {1, 2};
       },
       "", testing_support::At("/loads/0/force", {"node 3"})},
      {"bad_analysis", kTruss, [](json& j) { j["analysis"] = "dynamic"; }, "",
       testing_support::At("/analysis", {"\"fixed-load\"", "\"arc-length\""})},
      {"zero_arc_length", kTruss, [](json& j) { j["arc_length"] = 0; }, "",
       testing_support::At("/arc_length", {"0"})},
      {"zero_steps", kTruss, [](json& j) { j["steps"] = 0; }, "",
       testing_support::At("/steps", {"0"})},
      {"fractional_steps", kTruss, [](json& j) { j["steps"] = 2.5; }, "",
       testing_support::At("/steps", {"2.5"})},
      {"load_with_arc_length", kTruss, [](json& j) { j["load"] = 1; }, "",
       testing_support::At("/load", {"\"analysis\"", "\"fixed-load\""})},
      {"negative_scale", kTruss, [](json& j) { j["force_scale"] = -1; }, "",
       testing_support::At("/force_scale", {"-1"})},
      {"control_on_support", kTruss,
       [](json& j) {
         j["control"] = {{"node", 3}, {"direction", "y"}};
       },
       "", testing_support::At("/control/direction", {"node 3"})},
      {"zero_thickness", kQ4, [](json& j) { j["thickness"] = 0; }, "",
       testing_support::At("/thickness", {"0"})},
      {"negative_E_q4", kQ4, [](json& j) { j["material"]["E"] = -5; }, "",
       testing_support::At("/material/E", {"-5"})},
      {"nu_half", kQ4, [](json& j) { j["material"]["nu"] = 0.5; }, "",
       testing_support::At("/material/nu", {"0.5"})},
      {"nu_minus_one", kQ4, [](json& j) { j["material"]["nu"] = -1; }, "",
       testing_support::At("/material/nu", {"-1"})},
      {"clockwise", kQ4,
       [](json& j) {
         j["elements"][1]["nodes"] = {2, 5, 6, 3};
       },
       "", testing_support::At("/elements/1/nodes")},
      {"zero_area", kQ4,
       [](json& j) {
         j["elements"][0]["nodes"] = {1, 2, 4, 5};
       },
       "", testing_support::At("/elements/0/nodes")},
      {"repeated_element_node", kQ4,
       [](json& j) {
         j["elements"][0]["nodes"] = {1, 2, 5, 1};
       },
       "", testing_support::At("/elements/0/nodes/3", {"node 1"})},
      {"three_node_element", kQ4,
       [](json& j) {
         j["elements"][0]["nodes"] = {1, 2, 5};
       },
       "", testing_support::At("/elements/0/nodes", {"3"})},
      {"edge_not_a_side", kQ4,
       [](json& j) {
         j["tractions"][0]["edges"][0] = {4, 6};
       },
       "", testing_support::At("/tractions/0/edges/0", {"node 4", "node 6"})},
      {"interior_edge", kQ4,
       [](json& j) {
         j["tractions"][0]["edges"][0] = {2, 5};
       },
       "", testing_support::At("/tractions/0/edges/0", {"node 2", "node 5"})},
      {"element_side_out_of_range", kQ4,
       [](json& j) {
         j["tractions"][0] = {{"element_sides", {{0, 4}}}, {"traction", {0, 1}}};
       },
       "", testing_support::At("/tractions/0/element_sides/0/1", {"4"})},
      {"large_deformation", kQ4, [](json& j) { j["deformation"] = "large"; }, "",
       testing_support::At("/deformation")},
      {"group_without_mesh", kQ4,
       [](json& j) {
         j["supports"][0] = {{"group", "left"}, {"fixed", {"x"}}};
       },
       "", testing_support::At("/supports/0/group")},
      {"mesh_and_nodes", kQ4,
       [](json& j) {
         j["mesh"] = {{"file", "x.msh"}};
       },
       "", testing_support::At("/nodes", {"\"mesh\"", "\"nodes\"", "\"elements\""})},
      {"lcp_q_size", kLcp,
       [](json& j) {
         j["q"] = {1, 2, 3};
       },
       "", testing_support::At("/q", {"2 x 2"})},
      {"lcp_ragged", kLcp,
       [](json& j) {
         j["M"][1] = {1, 2, 3};
       },
       "", testing_support::At("/M/1")},
      {"lcp_sparse_not_square", kLcp,
       [](json& j) {
         j["M"] = {{"rows", 2}, {"cols", 3}, {"entries", json::array()}};
       },
       "", testing_support::At("/M/cols", {"2 x 3"})},
      {"lcp_entry_out_of_range", kLcp,
       [](json& j) {
         j["M"] = {{"rows", 2}, {"cols", 2}, {"entries", {{5, 0, 1.0}}}};
       },
       "", testing_support::At("/M/entries/0/0", {"row 5"})},
      {"lcp_duplicate_entry", kLcp,
       [](json& j) {
         j["M"] = {{"rows", 2}, {"cols", 2}, {"entries", {{0, 0, 1.0}, {0, 0, 2.0}}}};
       },
       "", testing_support::At("/M/entries/1", {"/M/entries/0"})},
      {"lcp_wrong_M", kLcp, [](json& j) { j["M"] = 3; }, "", testing_support::At("/M")},
  };
}

TEST(IoProblemFileTest, EveryBadInputIsRefusedNamingFilePointerAndReason) {
  const auto dir = TempDir("bad");
  for (const BadCase& c : BadCases()) {
    std::string text = c.text;
    if (c.base != nullptr) {
      json j = json::parse(c.base);
      c.mutate(j);
      text = j.dump(2);
    }
    const auto path = (dir / (c.name + ".json")).string();
    WriteText(path, text);
    try {
      io::LoadProblemFile(path);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const io::InputError& e) {
      const std::string message = e.what();
      EXPECT_TRUE(testing_support::RefusedAt(message, path, c.expected)) << c.name;
    }
  }
}

TEST(IoProblemFileTest, TheBaseDocumentsOfTheBadCasesAreValid) {
  // Otherwise a bad case could be refused for a reason other than its own.
  for (const char* base : {kTruss, kQ4, kLcp}) {
    EXPECT_NO_THROW(io::ParseProblemFile(base, "base.json", ".")) << base;
  }
}

// --- Gmsh -------------------------------------------------------------------------------------

std::string ExampleMesh() {
  std::ifstream in(kExamples / "q4-block-gmsh.msh");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  // Built piecewise: GCC 12's -Wrestrict misfires on std::string::replace here.
  std::string out(text, 0, at);
  out.append(to);
  out.append(text, at + from.size(), std::string::npos);
  return out;
}

TEST(IoGmshTest, ReadsTheExampleMeshWithItsGroups) {
  const io::GmshMesh mesh = io::ParseGmsh(ExampleMesh(), "q4-block-gmsh.msh");
  EXPECT_EQ(mesh.node_tags.size(), 6u);
  ASSERT_EQ(mesh.quads.size(), 2u);
  EXPECT_EQ(mesh.quads[1], (std::array<std::int64_t, 4>{5, 2, 3, 6}));
  EXPECT_EQ(mesh.quad_tags[1], 7);
  std::map<std::string, const io::GmshMesh::Group*> groups;
  for (const auto& g : mesh.groups) groups[g.name] = &g;
  ASSERT_EQ(groups.size(), 4u);
  EXPECT_EQ(groups["bottom"]->dim, 1);
  EXPECT_EQ(groups["bottom"]->edges.size(), 2u);
  EXPECT_EQ(groups["bottom"]->nodes, (std::vector<std::int64_t>{1, 2, 5}));
  EXPECT_EQ(groups["top"]->nodes, (std::vector<std::int64_t>{3, 4, 6}));
  EXPECT_EQ(groups["pin"]->dim, 0);
  EXPECT_EQ(groups["pin"]->nodes, (std::vector<std::int64_t>{1}));
  EXPECT_DOUBLE_EQ(mesh.coordinates(5, 0), 1.0);  // node 6 at (1, 1)
  EXPECT_DOUBLE_EQ(mesh.coordinates(5, 1), 1.0);
}

TEST(IoGmshTest, RefusesOtherVersionsElementsAndBadReferences) {
  const std::string good = ExampleMesh();
  struct Case {
    std::string name;
    std::string text;
    testing_support::Refusal expected;
  } cases[] = {
      {"v22", Replace(good, "4.1 0 8", "2.2 0 8"), testing_support::At("line 2", {"'2.2'"})},
      {"v40", Replace(good, "4.1 0 8", "4 0 8"), testing_support::At("line 2", {"'4'"})},
      {"binary", Replace(good, "4.1 0 8", "4.1 1 8"), testing_support::At("line 2")},
      {"not_gmsh", "hello", testing_support::At("line 1")},
      {"triangle", Replace(good, "2 1 3 2\n6 1 5 6 4\n7 5 2 3 6", "2 1 2 1\n6 1 5 6"),
       testing_support::At("", {"type 2"})},
      {"second_order_line", Replace(good, "1 1 1 2\n2 1 5\n3 5 2", "1 1 8 1\n2 1 2 5"),
       testing_support::At("", {"type 8"})},
      {"unknown_node", Replace(good, "7 5 2 3 6", "7 5 2 3 60"),
       testing_support::At("", {"element 7", "node 60"})},
      {"truncated", good.substr(0, good.find("$EndElements") - 8),
       testing_support::At("", {"unexpected end of file"})},
      {"bad_number", Replace(good, "1 1 0\n$EndNodes", "1 one 0\n$EndNodes"),
       testing_support::At("", {"'one'"})},
  };
  for (const auto& c : cases) {
    try {
      io::ParseGmsh(c.text, "m.msh");
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const io::InputError& e) {
      const std::string message = e.what();
      EXPECT_TRUE(testing_support::RefusedAt(message, "m.msh", c.expected)) << c.name;
    }
  }
}

TEST(IoGmshTest, ProblemFileRefusesBadMeshesAndUnknownGroups) {
  const auto dir = TempDir("gmsh");
  json base;
  {
    std::ifstream in(kExamples / "q4-block-gmsh.json");
    base = json::parse(in);
  }
  const std::string good = ExampleMesh();
  struct Case {
    std::string name;
    std::string mesh;  // the mesh file's text ("" for none)
    std::function<void(json&)> mutate;
    testing_support::Refusal expected;  // in the mesh file or the problem file
  } cases[] = {
      {"unknown_group", good, [](json& j) { j["tractions"][0]["group"] = "topp"; },
       testing_support::At("/tractions/0/group", {"\"topp\""})},
      {"point_group_traction", good, [](json& j) { j["tractions"][0]["group"] = "pin"; },
       testing_support::At("/tractions/0/group")},
      {"missing_mesh", "", [](json&) {}, testing_support::At("", {"q4-block-gmsh.msh"})},
      {"clockwise", Replace(good, "7 5 2 3 6", "7 5 6 3 2"), [](json&) {},
       testing_support::At("element 7")},
      {"off_plane", Replace(good, "1 1 0\n$EndNodes", "1 1 0.5\n$EndNodes"), [](json&) {},
       testing_support::At("node 6", {"z = 0.5", "z = 0"})},
      {"version", Replace(good, "4.1 0 8", "2.2 0 8"), [](json&) {},
       testing_support::At("line 2", {"'2.2'"})},
  };
  for (const auto& c : cases) {
    const auto sub = dir / c.name;
    std::filesystem::create_directories(sub);
    if (!c.mesh.empty()) WriteText(sub / "q4-block-gmsh.msh", c.mesh);
    json j = base;
    c.mutate(j);
    WriteText(sub / "p.json", j.dump(2));
    try {
      io::LoadProblemFile((sub / "p.json").string());
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const io::InputError& e) {
      const std::string message = e.what();
      EXPECT_TRUE(testing_support::Names(message, c.expected.names)) << c.name;
      if (!c.expected.where.empty()) {
        EXPECT_NE(message.find(": " + c.expected.where + ": "), std::string::npos)
            << c.name << ": " << message << " does not point at " << c.expected.where;
      }
    }
  }
}

}  // namespace
}  // namespace cb
