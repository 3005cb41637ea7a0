// The VTK files of the saved states, read back: the elements' quantities as cell data (checked
// against closed forms), the obstacles as surfaces of their own, and a collection whose time
// is the step.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "harness/obstacle_geometry.h"
#include "model/obstacle.h"
#include "run_example.h"

namespace {

using cb::test_support::kExamples;
using cb::test_support::RunExample;

std::string Contents(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The numbers of the DataArray (or Array) named `name` in a VTK XML text.
std::vector<double> ArrayValues(const std::string& xml, const std::string& name) {
  const std::size_t at = xml.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const std::size_t begin = xml.find('>', at) + 1;
  const std::size_t end = xml.find("</", begin);
  std::istringstream in(xml.substr(begin, end - begin));
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

// The text between <Tag ...> and </Tag> (the first such element).
std::string Element(const std::string& xml, const std::string& tag) {
  const std::size_t begin = xml.find("<" + tag);
  const std::size_t end = xml.find("</" + tag + ">", begin);
  return begin == std::string::npos || end == std::string::npos ? ""
                                                                : xml.substr(begin, end - begin);
}

TEST(VtkFilesTest, Q4StressIsTheUniformUniaxialStressOfTheBlockOnTheFloor) {
  // A pressure p = 10 on the top of a block on a frictionless floor: sigma_yy = -p, the other
  // components 0, von Mises p, in every element (Q4 passes the patch test).
  const auto dir = RunExample("q4-block-on-floor.json", "vtk_q4");
  const std::string grid = Contents(dir / "vtk" / "q4-block-on-floor_0000.vtu");
  const std::string cell_data = Element(grid, "CellData");
  ASSERT_FALSE(cell_data.empty()) << grid;
  const std::map<std::string, double> expected = {
      {"stress_xx", 0.0}, {"stress_yy", -10.0}, {"stress_xy", 0.0}, {"von_mises_stress", 10.0}};
  for (const auto& [name, value] : expected) {
    const std::vector<double> values = ArrayValues(cell_data, name);
    ASSERT_EQ(values.size(), 4u) << name;  // one per element
    for (double v : values) EXPECT_NEAR(v, value, 1e-8) << name;
  }
  std::filesystem::remove_all(dir);
}

TEST(VtkFilesTest, TrussMemberForcesAreTheSeriesBarsAgainstTheWall) {
  // Two bars in series pulled against a wall 0.01 away: once it is reached both carry
  // N = k gap, k = 1 / (L1/EA1 + L2/EA2) = 200/3, whatever the load; the stress is N / A.
  const auto dir = RunExample("truss-2d-bar-wall.json", "vtk_truss");
  const std::string pvd = Contents(dir / "vtk" / "truss-2d-bar-wall.pvd");
  const std::string grid = Contents(dir / "vtk" / "truss-2d-bar-wall_0000.vtu");
  ASSERT_GT(ArrayValues(grid, "lambda").at(0), 1.0);  // past contact (lambda = 2/3)
  const double n = 200.0 / 3.0 * 0.01;
  const std::vector<double> force = ArrayValues(Element(grid, "CellData"), "axial_force");
  const std::vector<double> stress = ArrayValues(Element(grid, "CellData"), "axial_stress");
  ASSERT_EQ(force.size(), 2u);
  ASSERT_EQ(stress.size(), 2u);
  EXPECT_NEAR(force[0], n, 1e-9);
  EXPECT_NEAR(force[1], n, 1e-9);
  EXPECT_NEAR(stress[0], n / 1.0, 1e-9);  // A = 1
  EXPECT_NEAR(stress[1], n / 0.5, 1e-9);  // A = 0.5

  // The wall: the half-plane x > 1.01 drawn as its boundary line, past the body on both sides.
  const std::string wall = Contents(dir / "vtk" / "truss-2d-bar-wall_obstacles.vtp");
  std::vector<double> xyz;
  const std::string block = Element(Element(wall, "Points"), "DataArray");
  std::istringstream numbers(block.substr(block.find('>') + 1));
  for (double v; numbers >> v;) xyz.push_back(v);
  ASSERT_EQ(xyz.size(), 6u) << wall;
  EXPECT_DOUBLE_EQ(xyz[0], 1.01);
  EXPECT_DOUBLE_EQ(xyz[3], 1.01);
  EXPECT_LT(std::min(xyz[1], xyz[4]), 0.0);
  EXPECT_GT(std::max(xyz[1], xyz[4]), 0.0);
  EXPECT_NE(wall.find("NumberOfLines=\"1\""), std::string::npos);
  // Its id, as VTK's ASCII string: the bytes of "wall", then 0; its line's obstacle index 0.
  EXPECT_NE(wall.find("Name=\"id\" NumberOfTuples=\"1\" format=\"ascii\">119 97 108 108 0 <"),
            std::string::npos)
      << wall;
  EXPECT_EQ(ArrayValues(Element(wall, "CellData"), "obstacle"), std::vector<double>{0.0});
  // The collection: the reference, then the final state, each with the obstacles as block 1.
  EXPECT_NE(pvd.find("timestep=\"0\" group=\"\" part=\"0\" name=\"truss-2d-bar-wall\" "
                     "file=\"truss-2d-bar-wall_reference.vtu\""),
            std::string::npos)
      << pvd;
  EXPECT_NE(pvd.find("part=\"0\" name=\"truss-2d-bar-wall\" file=\"truss-2d-bar-wall_0000.vtu\""),
            std::string::npos)
      << pvd;
  EXPECT_NE(pvd.find("part=\"1\" name=\"obstacles\" file=\"truss-2d-bar-wall_obstacles.vtp\""),
            std::string::npos)
      << pvd;
  std::filesystem::remove_all(dir);
}

TEST(VtkFilesTest, TheCollectionsTimeIsTheArcLengthAndOnlyTheNewRunsFilesAreThere) {
  const auto dir = RunExample("truss-2d-bar-wall.json", "vtk_steps", "--save-every 10");
  // The reference at 0, then saves at steps 10, 20, 30, 40 and the final state at 40, which
  // replaces the save of 40; each at the arc length of the steps before it (theta = 0.05 each
  // here: steps.csv's arc_length), which, unlike lambda, grows along any path.
  const std::string pvd = Contents(dir / "vtk" / "truss-2d-bar-wall.pvd");
  std::vector<double> times;
  for (std::size_t at = pvd.find("timestep=\""); at != std::string::npos;
       at = pvd.find("timestep=\"", at + 1)) {
    times.push_back(std::stod(pvd.substr(at + 10)));
  }
  const std::vector<double> expected = {0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.5, 1.5, 2.0, 2.0};
  ASSERT_EQ(times.size(), expected.size()) << pvd;  // 5 times x (the body, the obstacles)
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_NEAR(times[k], expected[k], 1e-12) << k;
  EXPECT_NE(pvd.find("truss-2d-bar-wall_reference.vtu"), std::string::npos);
  EXPECT_NE(pvd.find("truss-2d-bar-wall_0004.vtu"), std::string::npos);  // the final state
  EXPECT_EQ(pvd.find("truss-2d-bar-wall_0003.vtu"), std::string::npos);  // replaced by it
  const std::string reference = Contents(dir / "vtk" / "truss-2d-bar-wall_reference.vtu");
  EXPECT_EQ(ArrayValues(reference, "step"), std::vector<double>{0.0});
  for (double u : ArrayValues(Element(reference, "PointData"), "displacement")) {
    EXPECT_EQ(u, 0.0);
  }
  const std::string grid = Contents(dir / "vtk" / "truss-2d-bar-wall_0001.vtu");
  EXPECT_EQ(ArrayValues(grid, "step"), std::vector<double>{20.0});

  // Overwritten by a run of another problem: none of the earlier run's VTK files remain.
  const std::string command = std::string(CONTACTBENCH_BINARY) + " run --problem-file " +
                              (kExamples / "q4-block-on-floor.json").string() +
                              " --formulation implicit-fb --overwrite --out " + dir.string() +
                              " 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "vtk")) {
    files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"q4-block-on-floor.pvd", "q4-block-on-floor_0000.vtu",
                                             "q4-block-on-floor_obstacles.vtp",
                                             "q4-block-on-floor_reference.vtu"}));
  std::filesystem::remove_all(dir);
}

cb::Point P(std::initializer_list<double> values) {
  cb::Point p(static_cast<Eigen::Index>(values.size()));
  Eigen::Index k = 0;
  for (double v : values) p[k++] = v;
  return p;
}

TEST(ObstacleGeometryTest, SurfacesLieOnTheObstaclesZeroLevelSet) {
  using cb::harness::BoxAround;
  using cb::harness::ObstacleSurface;
  const cb::harness::Box box3 = BoxAround({P({0.0, 0.0, 0.0}), P({1.0, 2.0, 3.0})});
  const cb::HalfSpace plane(P({0.0, 0.0, -1.0}), P({1.0, 1.0, 1.0}));
  const cb::Ball sphere(P({0.5, 1.0, 1.5}), 2.0, cb::Ball::Side::kSolid);
  const cb::Ball circle(P({3.0, -1.0}), 0.5, cb::Ball::Side::kCavity);
  const cb::Cylinder rod(P({0.0, 1.0, -2.0}), P({1.0, 0.0, 1.0}), 1.5, cb::Ball::Side::kSolid);
  for (const cb::Obstacle* o : std::vector<const cb::Obstacle*>{&plane, &sphere, &circle, &rod}) {
    const auto surface = ObstacleSurface(*o, box3);
    ASSERT_FALSE(surface.points.empty());
    for (const auto& p : surface.points) {
      cb::Point x(o->dim());
      for (int c = 0; c < o->dim(); ++c) x[c] = p[c];
      EXPECT_NEAR(o->Value(x), 0.0, 1e-12) << o->Describe();
    }
  }
  // The plane's quad covers the box's projection: every corner of the box projects into it.
  const auto quad = ObstacleSurface(plane, box3);
  ASSERT_EQ(quad.polygons.size(), 1u);
  EXPECT_EQ(quad.polygons[0].size(), 4u);
  EXPECT_EQ(ObstacleSurface(circle, box3).lines.at(0).front(),
            ObstacleSurface(circle, box3).lines.at(0).back());  // closed
  // The rod's tube spans the box along its axis: its two rims lie at the box's extreme
  // projections onto the axis, so every corner of the box projects between them.
  const auto tube = ObstacleSurface(rod, box3);
  const cb::harness::Point3 axis{1.0 / std::sqrt(2.0), 0.0, 1.0 / std::sqrt(2.0)};
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : tube.points) {
    const double s = p[0] * axis[0] + (p[2] + 2.0) * axis[2];
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  for (int k = 0; k < 8; ++k) {
    const double corner_x = (k & 1) ? box3.high[0] : box3.low[0];
    const double corner_z = (k & 4) ? box3.high[2] : box3.low[2];
    const double s = corner_x * axis[0] + (corner_z + 2.0) * axis[2];
    EXPECT_GE(s, lo - 1e-12);
    EXPECT_LE(s, hi + 1e-12);
  }
  EXPECT_FALSE(tube.polygons.empty());
}

}  // namespace
