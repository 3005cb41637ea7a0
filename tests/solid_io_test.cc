// Hexahedral solids through the files: a Gmsh 4.1 hexahedral mesh (tests/data/hex-block.geo,
// its mesh hex-block.msh committed beside it) run end to end by `contactbench run`, and the
// refusal of other 3-D element types.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/gmsh.h"
#include "io/problem_file.h"
#include "model/solid_hex8.h"
#include "refusal.h"
#include "run_contactbench.h"
#include "source_tree.h"

namespace cb {
namespace {

using ::cb::testing_support::At;
using ::cb::testing_support::RefusedAt;

const std::filesystem::path kData = ::cb::testing_support::SourceRoot() / "tests" / "data";

std::string ReadAll(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SolidIoTest, GmshHexahedralMeshReadsWithItsGroups) {
  const io::GmshMesh mesh = io::ReadGmsh((kData / "hex-block.msh").string());
  EXPECT_EQ(mesh.hexes.size(), 4u);
  EXPECT_EQ(mesh.node_tags.size(), 18u);
  bool found_top = false;
  for (const auto& g : mesh.groups) {
    if (g.name != "top") continue;
    found_top = true;
    EXPECT_EQ(g.dim, 2);
    EXPECT_EQ(g.faces.size(), 4u);
    EXPECT_EQ(g.nodes.size(), 9u);
  }
  EXPECT_TRUE(found_top);
}

// The block on a frictionless floor under a uniform top pressure p, symmetry supports on
// x = 0 and y = 0: uniform stress, uz = -p z / E, ux = nu p x / E, uy = nu p y / E.
TEST(SolidIoTest, GmshHexahedralBlockRunsEndToEnd) {
  const auto out = std::filesystem::temp_directory_path() / "contactbench_solid_io_hex_block";
  std::filesystem::remove_all(out);
  const testing_support::CliOutcome run =
      testing_support::RunContactbench("run --problem-file " + (kData / "hex-block.json").string() +
                                       " --formulation implicit-fb --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.output;

  std::ifstream solution(out / "solution.csv");
  std::string line;
  std::getline(solution, line);
  EXPECT_EQ(line, "step,node,x,y,z,ux,uy,uz");
  int rows = 0;
  while (std::getline(solution, line)) {
    double v[8];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2],
                          &v[3], &v[4], &v[5], &v[6], &v[7]),
              8)
        << line;
    const double x = v[2], y = v[3], z = v[4];
    EXPECT_NEAR(v[5], 0.25 * 10.0 * x / 1000.0, 1e-10) << line;
    EXPECT_NEAR(v[6], 0.25 * 10.0 * y / 1000.0, 1e-10) << line;
    EXPECT_NEAR(v[7], -10.0 * z / 1000.0, 1e-10) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 18);
  // The VTK file has hexahedra (cell type 12) and the von Mises stress per cell: p = 10 for
  // the uniaxial stress.
  const std::string vtu = ReadAll(out / "vtk" / "hex-block_0000.vtu");
  EXPECT_NE(vtu.find(" 12 12 12 12"), std::string::npos);
  const auto at = vtu.find("Name=\"von_mises_stress\"");
  ASSERT_NE(at, std::string::npos);
  double von_mises = 0.0;
  std::sscanf(vtu.c_str() + vtu.find('\n', at) + 1, "%lf", &von_mises);
  EXPECT_NEAR(von_mises, 10.0, 1e-8);
}

TEST(SolidIoTest, OtherThreeDimensionalElementTypesAreRefusedWithTheWayToHexahedra) {
  const std::string tetrahedra =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
      "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n";
  try {
    io::ParseGmsh(tetrahedra, "tet.msh");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    // The type refused, the type to use, and the Gmsh commands that make and write it.
    EXPECT_TRUE(RefusedAt(what, "tet.msh", At("", {"type 4", "type 5", "Recombine", "msh41"})));
  }
}

TEST(SolidIoTest, InlineHexahedronAndCylinderRoundTrip) {
  // One unit cube (large deformation) resting in a pipe along x: inline nodes and elements.
  const std::string text = R"({
    "kind": "solid-hex8", "deformation": "large", "material": {"E": 100.0, "nu": 0.3},
    "nodes": [{"id": 1, "x": [0, 0, 0]}, {"id": 2, "x": [1, 0, 0]}, {"id": 3, "x": [1, 1, 0]},
              {"id": 4, "x": [0, 1, 0]}, {"id": 5, "x": [0, 0, 1]}, {"id": 6, "x": [1, 0, 1]},
              {"id": 7, "x": [1, 1, 1]}, {"id": 8, "x": [0, 1, 1]}],
    "elements": [{"nodes": [1, 2, 3, 4, 5, 6, 7, 8]}],
    "supports": [{"node": 1, "fixed": ["x", "y"]}, {"node": 2, "fixed": ["y"]},
                 {"node": 4, "fixed": ["x"]}],
    "tractions": [{"faces": [[5, 6, 7, 8]], "traction": [0, 0, -1]}],
    "obstacles": [{"id": "pipe", "type": "cylinder", "point": [0, 0.5, 0.5], "axis": [1, 0, 0],
                   "radius": 2.0, "side": "cavity"}],
    "contact_pairs": [{"node": 1, "obstacle": "pipe"}, {"node": 2, "obstacle": "pipe"},
                      {"node": 3, "obstacle": "pipe"}, {"node": 4, "obstacle": "pipe"}],
    "length_scale": 0.1, "force_scale": 1.0, "analysis": "arc-length", "arc_length": 0.1,
    "steps": 5})";
  const Problem p = io::ParseProblemFile(text, "cube.json", ".");
  ASSERT_NE(p.body, nullptr);
  const auto* hex = dynamic_cast<const SolidHex8*>(&p.body->body());
  ASSERT_NE(hex, nullptr);
  EXPECT_EQ(hex->kinematics(), SolidKinematics::kLargeStrain);
  EXPECT_NEAR(p.model->load_pattern().sum(), -1.0, 1e-14);  // traction x area
  const Problem q = io::ParseProblemFile(io::ProblemToJson(p), "cube.json", ".");
  Vec pa, pb;
  const Vec u = Vec::Constant(p.model->num_dofs(), 0.05);
  p.model->Gaps(u, &pa);
  q.model->Gaps(u, &pb);
  EXPECT_LT((pa - pb).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(p.model->Energy(u), q.model->Energy(u), 1e-14);
  // An interior or unknown face is refused with the reason.
  std::string bad = text;
  bad.replace(bad.find("[[5, 6, 7, 8]]"), 14, "[[1, 2, 6, 7]]");
  EXPECT_THROW(io::ParseProblemFile(bad, "cube.json", "."), std::invalid_argument);
}

// The message of a refused problem file, "accepted" when it is read.
std::string RefusalOf(const std::string& text, const std::string& directory = ".") {
  try {
    io::ParseProblemFile(text, "hex.json", directory);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

// A hexahedron listed twice (in any node order) doubles its stiffness silently: refused, as
// coincident nodes of a Gmsh mesh are (issue 30).
TEST(SolidIoTest, AHexahedronListedTwiceAndCoincidentGmshNodesAreRefused) {
  const std::string one = R"({
    "kind": "solid-hex8", "material": {"E": 100.0, "nu": 0.3},
    "nodes": [{"id": 1, "x": [0, 0, 0]}, {"id": 2, "x": [1, 0, 0]}, {"id": 3, "x": [1, 1, 0]},
              {"id": 4, "x": [0, 1, 0]}, {"id": 5, "x": [0, 0, 1]}, {"id": 6, "x": [1, 0, 1]},
              {"id": 7, "x": [1, 1, 1]}, {"id": 8, "x": [0, 1, 1]}],
    "elements": [{"nodes": [1, 2, 3, 4, 5, 6, 7, 8]}],
    "supports": [{"node": 1, "fixed": ["x", "y", "z"]}, {"node": 2, "fixed": ["y", "z"]},
                 {"node": 4, "fixed": ["x", "z"]}, {"node": 3, "fixed": ["z"]}],
    "loads": [{"node": 7, "force": [0, 0, -1]}],
    "length_scale": 0.1, "force_scale": 1.0, "analysis": "fixed-load", "load": 1.0})";
  ASSERT_EQ(RefusalOf(one), "accepted");
  std::string twice = one;
  const std::string element = "[1, 2, 3, 4, 5, 6, 7, 8]}]";
  twice.replace(twice.find(element), element.size(),
                "[1, 2, 3, 4, 5, 6, 7, 8]}, {\"nodes\": [2, 3, 4, 1, 6, 7, 8, 5]}]");
  const std::string refusal = RefusalOf(twice);
  EXPECT_TRUE(RefusedAt(refusal, "hex.json", At("/elements/1/nodes", {"/elements/0"})));

  // hex-block.msh with its second node moved onto its first.
  std::string mesh = ReadAll(kData / "hex-block.msh");
  const auto dir = std::filesystem::temp_directory_path() / "contactbench_solid_io_coincident";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const io::GmshMesh g = io::ReadGmsh((kData / "hex-block.msh").string());
  std::ostringstream first, second;
  first.precision(17);
  second.precision(17);
  first << g.coordinates(0, 0) << " " << g.coordinates(0, 1) << " " << g.coordinates(0, 2);
  second << g.coordinates(1, 0) << " " << g.coordinates(1, 1) << " " << g.coordinates(1, 2);
  const auto at = mesh.find("\n" + second.str() + "\n");
  ASSERT_NE(at, std::string::npos) << "the mesh writes coordinates as " << second.str();
  mesh.replace(at + 1, second.str().size(), first.str());
  std::ofstream(dir / "hex-block.msh") << mesh;
  std::filesystem::copy_file(kData / "hex-block.json", dir / "hex-block.json");
  const std::string coincident = RefusalOf(ReadAll(dir / "hex-block.json"), dir.string());
  // The mesh file, the moved node and the node it now coincides with.
  EXPECT_TRUE(RefusedAt(
      coincident, (dir / "hex-block.msh").string(),
      At("node " + std::to_string(g.node_tags[1]), {"node " + std::to_string(g.node_tags[0])})));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
