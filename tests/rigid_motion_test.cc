// Tests of src/model/rigid_motion: which rigid-body motions supports and contact pairs restrain,
// on small trusses whose free motions are known by inspection.
#include "model/rigid_motion.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/body_contact_model.h"
#include "model/obstacle.h"
#include "model/truss.h"

namespace cb {
namespace {

using Obstacles = std::vector<std::shared_ptr<const Obstacle>>;

// The unit square (nodes (0,0), (1,0), (1,1), (0,1)) as a braced truss, scaled by `scale` and
// moved by `shift`; `fixed` lists (node, component) supports.
Truss Square(const std::vector<std::pair<int, int>>& fixed, double scale = 1.0,
             const Point& shift = Point::Zero(2)) {
  Mat xy(4, 2);
  xy << 0, 0, 1, 0, 1, 1, 0, 1;
  xy *= scale;
  xy.rowwise() += shift.transpose();
  std::vector<bool> supported(8, false);
  for (const auto& [node, c] : fixed) supported[node * 2 + c] = true;
  const std::vector<TrussMember> members = {
      {0, 1, 1.0, 1.0}, {1, 2, 1.0, 1.0}, {2, 3, 1.0, 1.0}, {3, 0, 1.0, 1.0}, {0, 2, 1.0, 1.0}};
  return Truss(xy, members, supported);
}

// The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) with all six edges as members.
Truss Tetrahedron(const std::vector<std::pair<int, int>>& fixed) {
  Mat xyz(4, 3);
  xyz << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  std::vector<bool> supported(12, false);
  for (const auto& [node, c] : fixed) supported[node * 3 + c] = true;
  std::vector<TrussMember> members;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) members.push_back({i, j, 1.0, 1.0});
  }
  return Truss(xyz, members, supported);
}

constexpr int kX = 0, kY = 1, kZ = 2;

TEST(RigidMotionTest, NothingHoldsABodyWithoutSupportsOrPairs) {
  const RigidMotionRestraint r = CheckRigidMotionRestraint(Square({}), {}, {});
  EXPECT_EQ(r.modes, 3);
  EXPECT_EQ(r.constraints, 0);
  EXPECT_EQ(r.restrained, 0);
  EXPECT_EQ(r.free(), 3);
  EXPECT_FALSE(r.free_example.empty());
}

TEST(RigidMotionTest, APinLeavesTheRotationFree) {
  const RigidMotionRestraint r = CheckRigidMotionRestraint(Square({{0, kX}, {0, kY}}), {}, {});
  EXPECT_EQ(r.constraints, 2);
  EXPECT_EQ(r.free(), 1);
  EXPECT_EQ(r.free_example, "rotation about z");
}

TEST(RigidMotionTest, APinAndARollerAcrossTheirLineHoldThePlaneBody) {
  const RigidMotionRestraint r =
      CheckRigidMotionRestraint(Square({{0, kX}, {0, kY}, {1, kY}}), {}, {});
  EXPECT_EQ(r.constraints, 3);
  EXPECT_EQ(r.restrained, 3);
  EXPECT_EQ(r.free(), 0);
  EXPECT_TRUE(r.free_example.empty());
}

TEST(RigidMotionTest, ARollerAlongTheLineThroughThePinDoesNotStopTheRotation) {
  // Node 1 lies on the x-axis through the pinned node 0: rotating about node 0 moves it in y
  // only, which its x-roller allows.
  const RigidMotionRestraint r =
      CheckRigidMotionRestraint(Square({{0, kX}, {0, kY}, {1, kX}}), {}, {});
  EXPECT_EQ(r.constraints, 3);
  EXPECT_EQ(r.free(), 1);
  EXPECT_EQ(r.free_example, "rotation about z");
}

TEST(RigidMotionTest, SupportsInOneDirectionLeaveTheOtherTranslation) {
  const RigidMotionRestraint r = CheckRigidMotionRestraint(Square({{0, kY}, {1, kY}}), {}, {});
  EXPECT_EQ(r.free(), 1);
  EXPECT_EQ(r.free_example, "translation in x");
}

TEST(RigidMotionTest, ContactNormalsRestrainLikeSupports) {
  // A floor below (the obstacle is y < 0: its normal points down, into it) under the two bottom
  // nodes holds y and the rotation; a wall left of node 0 (x < 0) then holds x.
  const Obstacles floor = {
      std::make_shared<HalfSpace>(Point(Eigen::Vector2d(0, 0)), Point(Eigen::Vector2d(0, -1))),
      std::make_shared<HalfSpace>(Point(Eigen::Vector2d(0, 0)), Point(Eigen::Vector2d(-1, 0)))};
  const Truss body = Square({});
  const std::vector<ContactPair> on_floor = {{0, 0}, {1, 0}};
  const RigidMotionRestraint standing = CheckRigidMotionRestraint(body, floor, on_floor);
  EXPECT_EQ(standing.constraints, 2);
  EXPECT_EQ(standing.free(), 1);
  EXPECT_EQ(standing.free_example, "translation in x");

  std::vector<ContactPair> cornered = on_floor;
  cornered.push_back({0, 1});
  const RigidMotionRestraint held = CheckRigidMotionRestraint(body, floor, cornered);
  EXPECT_EQ(held.constraints, 3);
  EXPECT_EQ(held.free(), 0);
}

TEST(RigidMotionTest, TheAnswerDoesNotDependOnTheBodysSizeOrPlace) {
  const std::vector<std::vector<std::pair<int, int>>> supports = {
      {}, {{0, kX}, {0, kY}}, {{0, kX}, {0, kY}, {1, kX}}, {{0, kY}, {1, kY}}, {{2, kX}, {3, kY}}};
  for (const auto& fixed : supports) {
    const RigidMotionRestraint unit = CheckRigidMotionRestraint(Square(fixed), {}, {});
    const RigidMotionRestraint big =
        CheckRigidMotionRestraint(Square(fixed, 1e6, Point(Eigen::Vector2d(3e7, -2e7))), {}, {});
    const RigidMotionRestraint small =
        CheckRigidMotionRestraint(Square(fixed, 1e-6, Point(Eigen::Vector2d(1.0, 2.0))), {}, {});
    for (const RigidMotionRestraint* r : {&big, &small}) {
      EXPECT_EQ(r->restrained, unit.restrained) << fixed.size() << " supports";
      EXPECT_EQ(r->free_example, unit.free_example) << fixed.size() << " supports";
    }
  }
}

TEST(RigidMotionTest, ThreeTwoOneSupportsHoldASolidBody) {
  // Node 0 in x, y, z; node 1 (on the x-axis) in y, z; node 2 (on the y-axis) in z.
  const std::vector<std::pair<int, int>> fixed = {{0, kX}, {0, kY}, {0, kZ},
                                                  {1, kY}, {1, kZ}, {2, kZ}};
  const RigidMotionRestraint held = CheckRigidMotionRestraint(Tetrahedron(fixed), {}, {});
  EXPECT_EQ(held.modes, 6);
  EXPECT_EQ(held.restrained, 6);
  EXPECT_EQ(held.free(), 0);
  // Without node 2's support the body turns about the x-axis through nodes 0 and 1.
  const std::vector<std::pair<int, int>> hinged(fixed.begin(), fixed.end() - 1);
  const RigidMotionRestraint r = CheckRigidMotionRestraint(Tetrahedron(hinged), {}, {});
  EXPECT_EQ(r.free(), 1);
  EXPECT_EQ(r.free_example, "rotation about x");
}

TEST(RigidMotionTest, ABarInSpaceHasNoRotationAboutItsAxis) {
  Mat xyz(2, 3);
  xyz << 0, 0, 0, 2, 0, 0;
  const Truss bar(xyz, {{0, 1, 1.0, 1.0}});
  const RigidMotionRestraint r = CheckRigidMotionRestraint(bar, {}, {});
  EXPECT_EQ(r.modes, 5);
  EXPECT_EQ(r.free(), 5);
}

TEST(RigidMotionTest, PairsNamingUnknownNodesOrObstaclesThrow) {
  const Obstacles floor = {
      std::make_shared<HalfSpace>(Point(Eigen::Vector2d(0, 0)), Point(Eigen::Vector2d(0, -1)))};
  const Truss body = Square({});
  EXPECT_THROW(CheckRigidMotionRestraint(body, floor, {{4, 0}}), std::invalid_argument);
  EXPECT_THROW(CheckRigidMotionRestraint(body, floor, {{0, 1}}), std::invalid_argument);
  try {
    CheckRigidMotionRestraint(body, floor, {{0, 0}, {-1, 0}});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pairs[1].node"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cb
