// Rigid obstacles in 3-D (half-space, sphere, cylinder; solid and cavity) and a hexahedral
// solid against them: the cylinder's signed distance, and the gap Jacobian and curvature terms
// of the solid against all of them by finite differences (the obstacles' own derivatives are
// checked with the others in model_test.cc).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_model_check.h"
#include "fd_check.h"
#include "model/body_contact_model.h"
#include "model/obstacle.h"
#include "model/solid_hex8.h"
#include "problems/box_mesh.h"

namespace cb {
namespace {

constexpr double kFdTol = 1e-6;

Point P3(double x, double y, double z) {
  Point p(3);
  p << x, y, z;
  return p;
}

Vec RandomVec(int n, double scale, std::mt19937* rng) {
  std::uniform_real_distribution<double> dist(-scale, scale);
  Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = dist(*rng);
  return v;
}

std::vector<std::shared_ptr<const Obstacle>> Obstacles3D() {
  return {
      std::make_shared<HalfSpace>(P3(0.0, 0.0, -0.1), P3(0.1, 0.2, -1.0)),
      std::make_shared<Ball>(P3(0.5, 0.5, -2.0), 2.0, Ball::Side::kSolid),
      std::make_shared<Ball>(P3(0.5, 0.5, 0.5), 2.5, Ball::Side::kCavity),
      std::make_shared<Cylinder>(P3(0.3, -1.0, -1.5), P3(1.0, 0.5, 0.2), 1.4,
                                 Cylinder::Side::kSolid),
      std::make_shared<Cylinder>(P3(0.5, 0.5, 0.5), P3(0.0, 0.0, 3.0), 2.0,
                                 Cylinder::Side::kCavity),
  };
}

TEST(SolidContactTest, CylinderIsASignedDistancePositiveInside) {
  // The rod of radius 1 along z through (1, 0, *).
  const Cylinder rod(P3(1.0, 0.0, 5.0), P3(0.0, 0.0, 2.0), 1.0, Cylinder::Side::kSolid);
  EXPECT_DOUBLE_EQ(rod.Value(P3(1.5, 0.0, -3.0)), 0.5);  // inside, 0.5 from the surface
  EXPECT_DOUBLE_EQ(rod.Value(P3(1.0, 3.0, 7.0)), -2.0);  // outside, 2 away
  EXPECT_TRUE(rod.Gradient(P3(1.0, 3.0, 0.0)).isApprox(P3(0.0, -1.0, 0.0)));
  // Curvature 1/rho across the axis, none along it: the pipe's Hessian at (1, 0.5, 0).
  const Cylinder pipe(P3(1.0, 0.0, 5.0), P3(0.0, 0.0, 2.0), 1.0, Cylinder::Side::kCavity);
  EXPECT_DOUBLE_EQ(pipe.Value(P3(1.0, 0.5, 0.0)), -0.5);
  const PointMat h = pipe.Hessian(P3(1.0, 0.5, 0.0));
  EXPECT_NEAR(h(0, 0), 2.0, 1e-15);
  EXPECT_NEAR(h(1, 1), 0.0, 1e-15);
  EXPECT_NEAR(h(2, 2), 0.0, 1e-15);
  // On the axis: finite, a unit gradient normal to the axis.
  const Point g = rod.Gradient(P3(1.0, 0.0, 0.0));
  EXPECT_NEAR(g.norm(), 1.0, 1e-15);
  EXPECT_NEAR(g[2], 0.0, 1e-15);
  EXPECT_NE(pipe.Describe().find("cavity cylinder"), std::string::npos);
  auto bad = [](const Point& p, const Point& e, double a) {
    return [=] { Cylinder(p, e, a, Cylinder::Side::kSolid); };
  };
  EXPECT_THROW(bad(P3(0, 0, 0), P3(0, 0, 0), 1.0)(), std::invalid_argument);
  EXPECT_THROW(bad(P3(0, 0, 0), P3(0, 0, 1), 0.0)(), std::invalid_argument);
  EXPECT_THROW(bad(Point::Zero(2), Point::Zero(2), 1.0)(), std::invalid_argument);
}

// A large-deformation hexahedral block against every 3-D obstacle: the nodes of its bottom
// face against the flat and curved ones, some supported components among them.
TEST(SolidContactTest, HexahedralBodyGapDerivativesMatchFiniteDifferences) {
  const BoxMesh mesh = MakeBoxMesh({{2, 2, 1}, {1.0, 1.0, 0.5}, {1.0, 1.0, 1.0}});
  std::vector<bool> fixed(3 * mesh.coordinates.rows(), false);
  fixed[3 * mesh.node(0, 0, 0) + 0] = true;
  fixed[3 * mesh.node(1, 0, 0) + 1] = true;
  auto body =
      std::make_shared<SolidHex8>(mesh.coordinates, mesh.elements, SolidMaterial{100.0, 0.3},
                                  SolidKinematics::kLargeStrain, fixed);
  std::vector<ContactPair> pairs;
  const auto bottom = mesh.FaceNodes(2, 0);
  for (int obstacle = 0; obstacle < 5; ++obstacle) {
    for (int node : bottom) pairs.push_back({node, obstacle});
  }
  const BodyContactModel model(body, Obstacles3D(), pairs, Vec::Zero(body->num_dofs()));
  EXPECT_FALSE(model.is_linear());
  std::mt19937 rng(32);
  const Vec u = RandomVec(model.num_dofs(), 0.1, &rng);
  const Vec r = -RandomVec(model.num_pairs(), 1.0, &rng).cwiseAbs();
  fd_check::ExpectGapDerivativesMatch(model, u, r, kFdTol);
}

}  // namespace
}  // namespace cb
