// Tests of the contact model layer (docs/method.md section 1): obstacles, dof maps, the truss, the
// plane-stress Q4 body and the body/obstacle contact model. Derivatives are checked against
// central finite differences at seeded random, non-trivial points; known answers pin values.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <numbers>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contact_model_check.h"
#include "elastic_body_check.h"
#include "fd_check.h"
#include "model/body_contact_model.h"
#include "model/elastic_body.h"
#include "model/obstacle.h"
#include "model/plane_stress_q4.h"
#include "model/truss.h"
#include "refusal.h"

namespace cb {
namespace {

using ::cb::fd_check::FiniteDifferenceGradient;
using ::cb::fd_check::FiniteDifferenceJacobian;

constexpr double kFdTol = 1e-6;

Vec RandomVec(int n, double scale, std::mt19937* rng) {
  std::uniform_real_distribution<double> dist(-scale, scale);
  Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = dist(*rng);
  return v;
}

Point MakePoint(std::initializer_list<double> values) {
  Point p(static_cast<Eigen::Index>(values.size()));
  int i = 0;
  for (double v : values) p[i++] = v;
  return p;
}

Mat Dense(const SpMat& m) { return Mat(m); }

// Expects `statement` to throw std::invalid_argument whose message names each of `names` (the
// input at fault, the field, the value), whatever its wording (refusal.h).
template <typename F>
void ExpectInvalidNaming(F&& statement, const std::vector<std::string>& names) {
  try {
    statement();
    ADD_FAILURE() << "no exception; expected one naming " << names.front();
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(testing_support::Names(e.what(), names));
  }
}

// The refusal names `name` (the field or the input at fault).
template <typename F>
void ExpectInvalid(F&& statement, const std::string& name) {
  ExpectInvalidNaming(std::forward<F>(statement), {name});
}

// --- fixtures -----------------------------------------------------------------------------

// A 2-D Warren truss of 4 panels: lower chord nodes 0..4, upper chord nodes 5..8. Node 0 is
// pinned, node 4 is on a roller (y fixed).
std::shared_ptr<Truss> MakeTruss2D() {
  Mat xy(9, 2);
  for (int i = 0; i < 5; ++i) xy.row(i) << 1.0 * i, 0.0;
  for (int i = 0; i < 4; ++i) xy.row(5 + i) << 0.5 + i, 0.8;
  std::vector<TrussMember> members;
  auto add = [&](int i, int j, double area) { members.push_back({i, j, 200.0, area}); };
  for (int i = 0; i < 4; ++i) add(i, i + 1, 0.02 + 0.01 * i);                  // lower chord
  for (int i = 0; i < 3; ++i) add(5 + i, 6 + i, 0.03);                         // upper chord
  for (int i = 0; i < 4; ++i) add(i, 5 + i, 0.015), add(5 + i, i + 1, 0.025);  // diagonals
  std::vector<bool> fixed(18, false);
  fixed[0] = fixed[1] = true;  // node 0 pinned
  fixed[9] = true;             // node 4, y
  return std::make_shared<Truss>(xy, members, fixed);
}

// A 3-D truss: a square base (nodes 0..3), a top node 4 and a mid node 5, all connected. Node 0
// pinned, node 1 fixed in z only.
std::shared_ptr<Truss> MakeTruss3D() {
  Mat xyz(6, 3);
  xyz << 0, 0, 0,     //
      1.2, 0, 0,      //
      1.1, 0.9, 0.1,  //
      -0.1, 1.0, 0,   //
      0.5, 0.4, 1.3,  //
      0.6, 0.5, 0.5;
  std::vector<TrussMember> members;
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j < 6; ++j) members.push_back({i, j, 70.0 + 5.0 * i, 0.01 + 0.002 * j});
  }
  std::vector<bool> fixed(18, false);
  fixed[0] = fixed[1] = fixed[2] = true;
  fixed[5] = true;
  return std::make_shared<Truss>(xyz, members, fixed);
}

// Structured nx x ny Q4 mesh of [0, w] x [0, h]; node (i, j) is j * (nx + 1) + i. Interior nodes
// are displaced by up to `distortion` times the element size (boundary edges stay straight).
Mat GridCoordinates(int nx, int ny, double w, double h, double distortion, std::mt19937* rng) {
  std::uniform_real_distribution<double> dist(-distortion, distortion);
  Mat xy((nx + 1) * (ny + 1), 2);
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      double x = w * i / nx;
      double y = h * j / ny;
      if (i > 0 && i < nx && j > 0 && j < ny && rng != nullptr) {
        x += dist(*rng) * w / nx;
        y += dist(*rng) * h / ny;
      }
      xy.row(j * (nx + 1) + i) << x, y;
    }
  }
  return xy;
}

std::vector<PlaneStressQ4::Element> GridElements(int nx, int ny) {
  std::vector<PlaneStressQ4::Element> elements;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int n0 = j * (nx + 1) + i;
      elements.push_back({n0, n0 + 1, n0 + nx + 2, n0 + nx + 1});
    }
  }
  return elements;
}

const PlaneStressMaterial kSteelish{210.0, 0.3, 0.05};

// --- obstacles ------------------------------------------------------------------------------

std::vector<std::shared_ptr<const Obstacle>> AllObstacles() {
  return {
      std::make_shared<HalfSpace>(MakePoint({0.3, -0.2}), MakePoint({1.0, -2.0})),
      std::make_shared<HalfSpace>(MakePoint({0.1, 0.2, -0.3}), MakePoint({-0.5, 0.7, 2.0})),
      std::make_shared<Ball>(MakePoint({0.4, -0.3}), 1.5, Ball::Side::kSolid),
      std::make_shared<Ball>(MakePoint({0.4, -0.3}), 1.5, Ball::Side::kCavity),
      std::make_shared<Ball>(MakePoint({-0.2, 0.1, 0.5}), 2.0, Ball::Side::kSolid),
      std::make_shared<Ball>(MakePoint({-0.2, 0.1, 0.5}), 2.0, Ball::Side::kCavity),
      std::make_shared<Cylinder>(MakePoint({0.3, -1.0, -1.5}), MakePoint({1.0, 0.5, 0.2}), 1.4,
                                 Cylinder::Side::kSolid),
      std::make_shared<Cylinder>(MakePoint({0.5, 0.5, 0.5}), MakePoint({0.0, 0.0, 3.0}), 2.0,
                                 Cylinder::Side::kCavity),
  };
}

TEST(ModelTest, ObstacleGradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(20240601);
  for (const auto& obstacle : AllObstacles()) {
    SCOPED_TRACE(obstacle->Describe());
    const int dim = obstacle->dim();
    for (int trial = 0; trial < 5; ++trial) {
      const Vec x = RandomVec(dim, 2.0, &rng) + Vec::Constant(dim, 0.7);
      auto value = [&](const Vec& y) { return obstacle->Value(Point(y)); };
      auto gradient = [&](const Vec& y) { return Vec(obstacle->Gradient(Point(y))); };
      const Vec grad = obstacle->Gradient(Point(x));
      EXPECT_NEAR(grad.norm(), 1.0, 1e-14);
      EXPECT_DERIVATIVE_NEAR(grad, FiniteDifferenceGradient(value, x), kFdTol);
      const Mat hess = obstacle->Hessian(Point(x));
      if (obstacle->is_curved()) {
        EXPECT_DERIVATIVE_NEAR(hess, FiniteDifferenceJacobian(gradient, x), kFdTol);
        EXPECT_LT((hess - hess.transpose()).norm(), 1e-14);
      } else {
        EXPECT_EQ(hess.norm(), 0.0);
      }
    }
  }
}

TEST(ModelTest, ObstacleValuesAreSignedDistancesPositiveInside) {
  // Floor y < 0: normal (0, -3) is normalised.
  const HalfSpace floor(MakePoint({5.0, 0.0}), MakePoint({0.0, -3.0}));
  EXPECT_DOUBLE_EQ(floor.Value(MakePoint({1.0, -0.5})), 0.5);
  EXPECT_DOUBLE_EQ(floor.Value(MakePoint({-7.0, 2.0})), -2.0);
  EXPECT_EQ(floor.Gradient(MakePoint({0.0, 0.0})), MakePoint({0.0, -1.0}));
  EXPECT_FALSE(floor.is_curved());

  const Ball solid(MakePoint({1.0, 1.0, 1.0}), 2.0, Ball::Side::kSolid);
  EXPECT_DOUBLE_EQ(solid.Value(MakePoint({1.5, 1.0, 1.0})), 1.5);   // inside the ball
  EXPECT_DOUBLE_EQ(solid.Value(MakePoint({1.0, 5.0, 1.0})), -2.0);  // outside, 2 away
  // The gradient points into the obstacle: towards the centre for a solid ball.
  EXPECT_TRUE(solid.Gradient(MakePoint({1.0, 4.0, 1.0})).isApprox(MakePoint({0.0, -1.0, 0.0})));

  const Ball cavity(MakePoint({0.0, 0.0}), 1.0, Ball::Side::kCavity);
  EXPECT_DOUBLE_EQ(cavity.Value(MakePoint({0.0, 0.25})), -0.75);  // inside the hole: a gap
  EXPECT_DOUBLE_EQ(cavity.Value(MakePoint({3.0, 0.0})), 2.0);     // penetrating the wall
  EXPECT_TRUE(cavity.Gradient(MakePoint({0.0, 0.5})).isApprox(MakePoint({0.0, 1.0})));
  // Hessian s (I - n n^T) / |x - c|: at (0, 0.5) it is diag(2, 0) for the cavity.
  const PointMat h = cavity.Hessian(MakePoint({0.0, 0.5}));
  EXPECT_NEAR(h(0, 0), 2.0, 1e-15);
  EXPECT_NEAR(h(1, 1), 0.0, 1e-15);
  EXPECT_NEAR(h(0, 1), 0.0, 1e-15);
  EXPECT_FALSE(floor.Describe().empty());
  EXPECT_NE(cavity.Describe().find("cavity"), std::string::npos);
}

TEST(ModelTest, BallAtItsCentreIsFinite) {
  for (auto side : {Ball::Side::kSolid, Ball::Side::kCavity}) {
    const Ball ball(MakePoint({0.5, -1.0, 2.0}), 1.0, side);
    const Point centre = MakePoint({0.5, -1.0, 2.0});
    EXPECT_DOUBLE_EQ(std::abs(ball.Value(centre)), 1.0);
    const Point g = ball.Gradient(centre);
    EXPECT_TRUE(g.allFinite());
    EXPECT_DOUBLE_EQ(g.norm(), 1.0);
    EXPECT_TRUE(ball.Hessian(centre).allFinite());
  }
}

TEST(ModelTest, ObstaclesRejectInvalidInput) {
  ExpectInvalid([] { HalfSpace(MakePoint({0, 0}), MakePoint({0, 0})); }, "zero normal");
  ExpectInvalid([] { HalfSpace(MakePoint({0, 0}), MakePoint({0, 1, 0})); }, "dimension");
  ExpectInvalid([] { HalfSpace(MakePoint({0}), MakePoint({1})); }, "expected 2 or 3");
  ExpectInvalid([] { HalfSpace(MakePoint({0, NAN}), MakePoint({0, 1})); }, "non-finite");
  ExpectInvalid([] { Ball(MakePoint({0, 0}), 0.0, Ball::Side::kSolid); }, "radius");
  ExpectInvalid([] { Ball(MakePoint({0, 0}), -1.0, Ball::Side::kCavity); }, "radius");
  ExpectInvalid([] { Ball(MakePoint({0}), 1.0, Ball::Side::kSolid); }, "expected 2 or 3");
}

// --- dof map and positions ------------------------------------------------------------------

TEST(ModelTest, DofMapNumbersFreeComponentsNodeByNode) {
  const DofMap all(3, 2);
  EXPECT_EQ(all.num_dofs(), 6);
  EXPECT_EQ(all.dof(2, 1), 5);
  const DofMap some(3, 2, {true, false, false, false, true, true});
  EXPECT_EQ(some.num_dofs(), 3);
  EXPECT_EQ(some.dof(0, 0), -1);
  EXPECT_EQ(some.dof(0, 1), 0);
  EXPECT_EQ(some.dof(1, 0), 1);
  EXPECT_EQ(some.dof(1, 1), 2);
  EXPECT_EQ(some.dof(2, 0), -1);
  EXPECT_EQ(some.dof(2, 1), -1);
  ExpectInvalid([] { DofMap(3, 2, std::vector<bool>(5, false)); }, "fixed");
  ExpectInvalid([] { DofMap(-1, 2); }, "negative");
  ExpectInvalid([] { DofMap(2, 0); }, "dimension");
}

TEST(ModelTest, PositionAddsDisplacementOnFreeComponentsOnly) {
  const auto truss = MakeTruss2D();
  Vec u = Vec::LinSpaced(truss->num_dofs(), 1.0, 2.0);
  // Node 0 is pinned: it stays at X. Node 4 has x free, y fixed.
  EXPECT_EQ(truss->Position(0, u), truss->reference(0));
  const Point x4 = truss->Position(4, u);
  EXPECT_DOUBLE_EQ(x4[0], truss->reference(4)[0] + u[truss->dofs().dof(4, 0)]);
  EXPECT_DOUBLE_EQ(x4[1], truss->reference(4)[1]);
}

// --- truss ----------------------------------------------------------------------------------

void CheckTrussDerivatives(const Truss& truss, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 3; ++trial) {
    const Vec u = RandomVec(truss.num_dofs(), scale, &rng);
    fd_check::ExpectBodyDerivativesMatch(truss, u, kFdTol);
    Vec f;
    truss.InternalForce(u, &f);
    // The one-pass call gives the same force and stiffness contributions to the last bit
    // (each contribution into its own slot here, with a scale).
    const std::size_t contributions = truss.StiffnessEntries().size();
    std::vector<int> slots(contributions);
    std::iota(slots.begin(), slots.end(), 0);
    std::vector<double> one_pass(contributions, 0.0), separate(contributions, 0.0);
    Vec f_one_pass;
    truss.InternalForceAndStiffness(u, &f_one_pass, -2.5, slots.data(), one_pass.data());
    truss.AddStiffness(u, -2.5, slots.data(), separate.data());
    EXPECT_EQ((f_one_pass - f).norm(), 0.0);
    EXPECT_EQ(one_pass, separate);
    EXPECT_GT(*std::max_element(separate.begin(), separate.end()), 0.0);
  }
}

TEST(ModelTest, TrussGradientAndStiffnessMatchFiniteDifferences2D) {
  // Displacements of up to 0.2 on members of length ~1: large rotations and strains.
  CheckTrussDerivatives(*MakeTruss2D(), 0.2, 11);
}

TEST(ModelTest, TrussGradientAndStiffnessMatchFiniteDifferences3D) {
  CheckTrussDerivatives(*MakeTruss3D(), 0.2, 12);
}

TEST(ModelTest, TrussSingleBarForceIsExactUnderLargeRotation) {
  const double e = 2.0e5, a = 3.0e-3, delta = 0.013;
  Mat xy(2, 2);
  xy << 0.2, 0.1, 1.7, 2.1;  // L = 2.5
  const Truss bar(xy, {{0, 1, e, a}}, {true, true, false, false});
  const double length = 2.5;
  EXPECT_DOUBLE_EQ(bar.ReferenceLength(0), length);
  // Node 1 moves to a position at distance L + delta from node 0 after a 70 degree rotation:
  // Biot strain is objective, so N = E A delta / L and the force is along the new axis.
  const double angle = 70.0 * std::numbers::pi / 180.0;
  const Eigen::Vector2d axis0(1.5 / length, 2.0 / length);
  const Eigen::Vector2d axis = Eigen::Rotation2Dd(angle) * axis0;
  Vec u(2);
  u = Eigen::Vector2d(0.2, 0.1) + (length + delta) * axis - Eigen::Vector2d(1.7, 2.1);
  const double expected = e * a * delta / length;
  EXPECT_NEAR(bar.MemberForce(0, u), expected, 1e-12 * expected);
  Vec f;
  bar.InternalForce(u, &f);
  EXPECT_NEAR((f - expected * Vec(axis)).norm(), 0.0, 1e-12 * expected);
  EXPECT_NEAR(bar.Energy(u), 0.5 * e * a * length * std::pow(delta / length, 2),
              1e-12 * expected * delta);
  // Tangent along the bar is E A / L, across it N / l.
  SpMat k;
  bar.Stiffness(u, &k);
  const Vec along = Vec(axis);
  const Vec across = Vec(Eigen::Vector2d(-axis[1], axis[0]));
  EXPECT_NEAR(along.dot(k * along), e * a / length, 1e-10 * e * a / length);
  EXPECT_NEAR(across.dot(k * across), expected / (length + delta), 1e-10 * e * a / length);
}

TEST(ModelTest, TrussStiffnessPatternIsReusedAcrossEvaluations) {
  const auto truss = MakeTruss3D();
  std::mt19937 rng(5);
  const Vec u1 = RandomVec(truss->num_dofs(), 0.2, &rng);
  const Vec u2 = RandomVec(truss->num_dofs(), 0.2, &rng);
  SpMat k;
  truss->Stiffness(u1, &k);
  const Mat k1 = Dense(k);
  const Eigen::Index nnz = k.nonZeros();
  const double* storage = k.valuePtr();
  truss->Stiffness(u2, &k);
  EXPECT_EQ(k.nonZeros(), nnz);
  EXPECT_EQ(k.valuePtr(), storage) << "the second fill reallocated";
  EXPECT_GT((Dense(k) - k1).norm(), 1e-3 * k1.norm()) << "values did not change with u";
  SpMat fresh;
  truss->Stiffness(u2, &fresh);
  EXPECT_EQ((Dense(k) - Dense(fresh)).norm(), 0.0);
  auto force = [&](const Vec& v) {
    Vec f;
    truss->InternalForce(v, &f);
    return f;
  };
  EXPECT_DERIVATIVE_NEAR(Dense(k), FiniteDifferenceJacobian(force, u2), kFdTol);
}

TEST(ModelTest, TrussRejectsInvalidInput) {
  Mat xy(3, 2);
  xy << 0, 0, 1, 0, 1, 1;
  const TrussMember good{0, 1, 1.0, 1.0};
  ExpectInvalidNaming([&] { Truss(xy, {good, {0, 3, 1.0, 1.0}}); }, {"member 1", "3"});
  ExpectInvalidNaming([&] { Truss(xy, {good, {-1, 2, 1.0, 1.0}}); }, {"member 1", "-1"});
  ExpectInvalidNaming([&] { Truss(xy, {good, {2, 2, 1.0, 1.0}}); }, {"member 1", "node 2"});
  ExpectInvalidNaming(
      [&] {
        Truss(xy, {good, {1, 2, 0.0, 1.0}});
      },
      {"member 1", "Young's modulus"});
  ExpectInvalidNaming([&] { Truss(xy, {good, {1, 2, 1.0, -2.0}}); }, {"member 1", "area"});
  Mat duplicate = xy;
  duplicate.row(2) = duplicate.row(1);
  ExpectInvalidNaming([&] { Truss(duplicate, {good, {1, 2, 1.0, 1.0}}); }, {"member 1", "length"});
  Mat bad = xy;
  bad(2, 1) = std::numeric_limits<double>::infinity();
  ExpectInvalidNaming([&] { Truss(bad, {good}); }, {"node 2", "coordinates"});
  ExpectInvalid([&] { Truss(Mat::Zero(3, 4), {}); }, "expected 2 or 3");
  ExpectInvalid([&] { Truss(xy, {good}, std::vector<bool>(5, false)); }, "fixed");
}

// --- plane-stress Q4 ------------------------------------------------------------------------

TEST(ModelTest, Q4GradientAndStiffnessMatchFiniteDifferences) {
  std::mt19937 rng(7);
  const int nx = 3, ny = 2;
  std::vector<bool> fixed(2 * (nx + 1) * (ny + 1), false);
  fixed[0] = fixed[1] = true;
  const PlaneStressQ4 body(GridCoordinates(nx, ny, 3.0, 2.0, 0.25, &rng), GridElements(nx, ny),
                           kSteelish, fixed);
  fd_check::ExpectBodyDerivativesMatch(body, RandomVec(body.num_dofs(), 0.1, &rng), kFdTol);
  EXPECT_TRUE(body.is_linear());
}

TEST(ModelTest, Q4StiffnessIsSymmetricPositiveSemidefiniteWithRigidModes) {
  std::mt19937 rng(8);
  const int nx = 4, ny = 3;
  const Mat xy = GridCoordinates(nx, ny, 2.0, 1.5, 0.3, &rng);
  const PlaneStressQ4 body(xy, GridElements(nx, ny), kSteelish);
  const Mat k = Dense(body.stiffness());
  EXPECT_EQ((k - k.transpose()).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::SelfAdjointEigenSolver<Mat> eig(k);
  const double top = eig.eigenvalues().maxCoeff();
  // Exactly three zero-energy modes (two translations, one rotation); no spurious modes.
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * top);
  EXPECT_LT(std::abs(eig.eigenvalues()[2]), 1e-12 * top);
  EXPECT_GT(eig.eigenvalues()[3], 1e-6 * top);
  // Rigid translation and infinitesimal rotation u = theta (-y, x) produce no force.
  Vec tx = Vec::Zero(body.num_dofs()), ty = tx, rot = tx;
  for (int n = 0; n < body.num_nodes(); ++n) {
    tx[2 * n] = 1.0;
    ty[2 * n + 1] = 1.0;
    rot[2 * n] = -xy(n, 1);
    rot[2 * n + 1] = xy(n, 0);
  }
  for (const Vec& mode : {tx, ty, rot}) {
    Vec f;
    body.InternalForce(mode, &f);
    EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-12 * top);
    EXPECT_LT(std::abs(body.Energy(mode)), 1e-12 * top);
  }
}

TEST(ModelTest, Q4SquareElementMatchesClosedForm) {
  // Closed-form stiffness of a square bilinear element with 2 x 2 Gauss (independent of size),
  // first row: E t / (1 - nu^2) [1/2 - nu/6, 1/8 + nu/8, -1/4 - nu/12, -1/8 + 3nu/8,
  // -1/4 + nu/12, -1/8 - nu/8, nu/6, 1/8 - 3nu/8].
  const double nu = 0.25, e = 3.0, t = 0.4;
  Mat xy(4, 2);
  xy << 1, 1, 3, 1, 3, 3, 1, 3;
  const PlaneStressQ4 body(xy, {{0, 1, 2, 3}}, {e, nu, t});
  const double c = e * t / (1.0 - nu * nu);
  Vec expected(8);
  expected << 0.5 - nu / 6, 0.125 + nu / 8, -0.25 - nu / 12, -0.125 + 3 * nu / 8, -0.25 + nu / 12,
      -0.125 - nu / 8, nu / 6, 0.125 - 3 * nu / 8;
  expected *= c;
  const Vec row0 = Dense(body.stiffness()).row(0).transpose();
  EXPECT_LT((row0 - expected).cwiseAbs().maxCoeff(), 1e-14 * c);
}

TEST(ModelTest, Q4PatchTestLinearFieldGivesExactStressResultants) {
  // A linear displacement field on a distorted mesh: constant strain, so K u equals the
  // consistent edge loads of the constant stress (interior nodes: zero) and the energy is
  // t area eps^T D eps / 2.
  std::mt19937 rng(9);
  const int nx = 4, ny = 3;
  const double w = 2.0, h = 1.5;
  const Mat xy = GridCoordinates(nx, ny, w, h, 0.3, &rng);
  const PlaneStressQ4 body(xy, GridElements(nx, ny), kSteelish);
  const double a11 = 1e-3, a12 = -4e-4, a21 = 7e-4, a22 = -2e-3;
  Vec u(body.num_dofs());
  for (int n = 0; n < body.num_nodes(); ++n) {
    u[2 * n] = a11 * xy(n, 0) + a12 * xy(n, 1) + 0.3;
    u[2 * n + 1] = a21 * xy(n, 0) + a22 * xy(n, 1) - 0.1;
  }
  const double nu = kSteelish.poisson_ratio;
  const double c = kSteelish.youngs_modulus / (1.0 - nu * nu);
  const Eigen::Vector3d strain(a11, a22, a12 + a21);
  Eigen::Matrix3d d;
  d << c, c * nu, 0, c * nu, c, 0, 0, 0, c * (1 - nu) / 2;
  const Eigen::Vector3d stress = d * strain;  // (sxx, syy, sxy)
  auto traction = [&](double nx_, double ny_) {
    return MakePoint({stress[0] * nx_ + stress[2] * ny_, stress[2] * nx_ + stress[1] * ny_});
  };
  Vec expected = Vec::Zero(body.num_dofs());
  auto node = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int i = 0; i < nx; ++i) {
    body.AddEdgeTraction(node(i, 0), node(i + 1, 0), traction(0, -1), &expected);
    body.AddEdgeTraction(node(i, ny), node(i + 1, ny), traction(0, 1), &expected);
  }
  for (int j = 0; j < ny; ++j) {
    body.AddEdgeTraction(node(0, j), node(0, j + 1), traction(-1, 0), &expected);
    body.AddEdgeTraction(node(nx, j), node(nx, j + 1), traction(1, 0), &expected);
  }
  Vec f;
  body.InternalForce(u, &f);
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 0.0);
  // The rigid translation in u is ~300 times the strain-induced displacements, so rounding
  // in K u is ~1e-16 |K| |u|: tolerances leave room for that cancellation.
  EXPECT_LT((f - expected).cwiseAbs().maxCoeff(), 1e-10 * scale);
  // Interior nodes carry no force.
  EXPECT_LT(std::abs(f[2 * node(2, 1)]) + std::abs(f[2 * node(2, 1) + 1]), 1e-10 * scale);
  const double exact_energy = 0.5 * kSteelish.thickness * w * h * strain.dot(stress);
  EXPECT_NEAR(body.Energy(u), exact_energy, 1e-9 * exact_energy);
}

TEST(ModelTest, Q4EdgeTractionAndNodalForceRespectSupports) {
  Mat xy(4, 2);
  xy << 0, 0, 2, 0, 2, 1, 0, 1;
  const PlaneStressQ4 body(xy, {{0, 1, 2, 3}}, kSteelish,
                           {true, true, false, true, false, false, false, false});
  ASSERT_EQ(body.num_dofs(), 5);
  Vec load = Vec::Zero(5);
  // Edge 1 -> 2 has length 1: each end gets traction * t * 1 / 2; node 1 y is supported.
  body.AddEdgeTraction(1, 2, MakePoint({4.0, -2.0}), &load);
  const double half = 0.5 * kSteelish.thickness;
  Vec expected(5);
  expected << 4.0 * half, 4.0 * half, -2.0 * half, 0.0, 0.0;
  EXPECT_LT((load - expected).norm(), 1e-15);
  AddNodalForce(body.dofs(), 3, MakePoint({1.0, 2.0}), &load);
  expected.tail(2) << 1.0, 2.0;
  EXPECT_LT((load - expected).norm(), 1e-15);
  ExpectInvalid(
      [&] {
        AddNodalForce(body.dofs(), 4, MakePoint({1.0, 2.0}), &load);
      },
      "unknown node");
  ExpectInvalid(
      [&] {
        AddNodalForce(body.dofs(), 3, MakePoint({1.0, 2.0, 3.0}), &load);
      },
      "components");
  Vec wrong(3);
  ExpectInvalid([&] { body.AddEdgeTraction(0, 1, MakePoint({1.0, 0.0}), &wrong); }, "size");
}

TEST(ModelTest, Q4AssemblyHasTheStructuredMeshPattern) {
  // n x n structured mesh: interior nodes couple to 9 nodes, edge nodes to 6, corners to 4,
  // each coupling a 2 x 2 block.
  const int n = 60;
  const PlaneStressQ4 body(GridCoordinates(n, n, 1.0, 1.0, 0.0, nullptr), GridElements(n, n),
                           kSteelish);
  const long expected = 4L * (9L * (n - 1) * (n - 1) + 6L * 4 * (n - 1) + 4L * 4);
  EXPECT_EQ(body.stiffness().nonZeros(), expected);
  EXPECT_TRUE(body.stiffness().isCompressed());
  // A rigid translation (both components) produces no force.
  Vec f;
  body.InternalForce(Vec::Ones(body.num_dofs()), &f);
  EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-12 * body.stiffness().coeff(0, 0));
}

TEST(ModelTest, Q4RejectsInvalidInput) {
  Mat xy(5, 2);
  xy << 0, 0, 1, 0, 1, 1, 0, 1, 2, 0;
  ExpectInvalid(
      [&] {
        PlaneStressQ4(xy, {{0, 3, 2, 1}}, kSteelish);
      },
      "element 0 has non-positive area or clockwise node order");
  ExpectInvalid(
      [&] {
        PlaneStressQ4(xy, {{0, 1, 2, 3}, {1, 4, 7, 2}}, kSteelish);
      },
      "element 1 names an unknown node 7");
  ExpectInvalid(
      [&] {
        PlaneStressQ4(xy, {{0, 1, 2, 3}, {1, 4, 2, 2}}, kSteelish);
      },
      "element 1 repeats node 2");
  Mat flat = xy;
  flat.row(2) << 2, 0;  // all four nodes on y = 0: zero area
  flat.row(3) << 1, 0;
  ExpectInvalid([&] { PlaneStressQ4(flat, {{0, 1, 2, 3}}, kSteelish); }, "element 0 has");
  ExpectInvalid([&] { PlaneStressQ4(xy, {{0, 1, 2, 3}}, {0.0, 0.3, 1.0}); }, "Young");
  ExpectInvalid([&] { PlaneStressQ4(xy, {{0, 1, 2, 3}}, {1.0, 0.5, 1.0}); }, "Poisson");
  ExpectInvalid([&] { PlaneStressQ4(xy, {{0, 1, 2, 3}}, {1.0, -1.0, 1.0}); }, "Poisson");
  ExpectInvalid([&] { PlaneStressQ4(xy, {{0, 1, 2, 3}}, {1.0, 0.3, 0.0}); }, "thickness");
  ExpectInvalid([&] { PlaneStressQ4(Mat::Zero(4, 3), {{0, 1, 2, 3}}, kSteelish); }, "columns");
  ExpectInvalid(
      [&] {
        PlaneStressQ4(xy, {{0, 1, 2, 3}}, kSteelish, std::vector<bool>(3));
      },
      "fixed");
}

// --- body contact model ---------------------------------------------------------------------

// The truss against a floor, a solid circle and a round cavity; pairs include a supported node
// (0), a node with one supported component (4) and nodes against several obstacles.
BodyContactModel MakeTrussContact2D() {
  auto truss = MakeTruss2D();
  std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<HalfSpace>(MakePoint({0.0, -0.1}), MakePoint({0.1, -1.0})),
      std::make_shared<Ball>(MakePoint({2.0, 2.5}), 1.5, Ball::Side::kSolid),
      std::make_shared<Ball>(MakePoint({2.0, 0.5}), 3.0, Ball::Side::kCavity),
  };
  std::vector<ContactPair> pairs = {{0, 0}, {1, 0}, {2, 0}, {4, 0}, {5, 1},
                                    {6, 1}, {7, 1}, {4, 2}, {8, 2}, {3, 2}};
  Vec load = Vec::Zero(truss->num_dofs());
  AddNodalForce(truss->dofs(), 6, MakePoint({0.0, -1.0}), &load);
  return BodyContactModel(truss, obstacles, pairs, load);
}

BodyContactModel MakeTrussContact3D() {
  auto truss = MakeTruss3D();
  std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<HalfSpace>(MakePoint({0.0, 0.0, -0.1}), MakePoint({0.0, 0.2, -1.0})),
      std::make_shared<Ball>(MakePoint({0.5, 0.5, 3.0}), 1.6, Ball::Side::kSolid),
      std::make_shared<Ball>(MakePoint({0.5, 0.5, 0.5}), 2.5, Ball::Side::kCavity),
  };
  std::vector<ContactPair> pairs = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 1},
                                    {5, 1}, {1, 2}, {4, 2}, {2, 2}};
  return BodyContactModel(truss, obstacles, pairs, Vec::Zero(truss->num_dofs()));
}

void CheckContactDerivatives(const BodyContactModel& model, unsigned seed) {
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 3; ++trial) {
    const Vec u = RandomVec(model.num_dofs(), 0.2, &rng);
    const Vec r =
        -RandomVec(model.num_pairs(), 1.0, &rng).cwiseAbs() - Vec::Constant(model.num_pairs(), 0.1);
    fd_check::ExpectGapDerivativesMatch(model, u, r, kFdTol);
  }
}

TEST(ModelTest, BodyContactGapJacobianAndCurvatureMatchFiniteDifferences2D) {
  const BodyContactModel model = MakeTrussContact2D();
  EXPECT_FALSE(model.is_linear());
  CheckContactDerivatives(model, 21);
}

TEST(ModelTest, BodyContactGapJacobianAndCurvatureMatchFiniteDifferences3D) {
  CheckContactDerivatives(MakeTrussContact3D(), 22);
}

TEST(ModelTest, GeneralisedReactionIsGapJacobianTransposeTimesR) {
  for (const BodyContactModel& model : {MakeTrussContact2D(), MakeTrussContact3D()}) {
    std::mt19937 rng(29);
    const Vec u = RandomVec(model.num_dofs(), 0.2, &rng);
    const Vec r = RandomVec(model.num_pairs(), 1.0, &rng);
    SpMat jac;
    model.GapJacobian(u, &jac);
    Vec reaction;
    model.GeneralisedReaction(u, r, &reaction);
    const Vec expected = jac.transpose() * r;
    EXPECT_LT((reaction - expected).lpNorm<Eigen::Infinity>(), 1e-14);
    // The interface's default (through the assembled Jacobian) agrees.
    Vec by_default;
    model.ContactModel::GeneralisedReaction(u, r, &by_default);
    EXPECT_LT((by_default - expected).lpNorm<Eigen::Infinity>(), 1e-14);
  }
}

// The one-pass evaluations a Newton iteration uses (residual: phi and grad phi^T r; Jacobian:
// grad phi and the curvature) give exactly what the single functions and the interface's
// defaults give, mixed flat and curved pairs included.
TEST(ModelTest, OnePassContactEvaluationsMatchTheSingleOnes) {
  for (const BodyContactModel& model : {MakeTrussContact2D(), MakeTrussContact3D()}) {
    std::mt19937 rng(31);
    const Vec u = RandomVec(model.num_dofs(), 0.2, &rng);
    const Vec r = RandomVec(model.num_pairs(), 1.0, &rng);
    Vec phi, reaction, phi_default, reaction_default;
    model.GapsAndReaction(u, r, &phi, &reaction);
    model.ContactModel::GapsAndReaction(u, r, &phi_default, &reaction_default);
    Vec phi_single, reaction_single;
    model.Gaps(u, &phi_single);
    model.GeneralisedReaction(u, r, &reaction_single);
    EXPECT_EQ((phi - phi_single).norm(), 0.0);
    EXPECT_EQ((reaction - reaction_single).norm(), 0.0);
    EXPECT_EQ((phi - phi_default).norm(), 0.0);
    EXPECT_EQ((reaction - reaction_default).norm(), 0.0);

    SpMat jac, curvature, jac_single, curvature_single;
    model.GapDerivatives(u, r, &jac, &curvature);
    model.GapJacobian(u, &jac_single);
    model.GapCurvature(u, r, &curvature_single);
    EXPECT_GT(Dense(curvature).norm(), 0.0);
    EXPECT_EQ((Dense(jac) - Dense(jac_single)).norm(), 0.0);
    EXPECT_EQ((Dense(curvature) - Dense(curvature_single)).norm(), 0.0);
    SpMat jac_default, curvature_default;
    model.ContactModel::GapDerivatives(u, r, &jac_default, &curvature_default);
    EXPECT_EQ((Dense(jac) - Dense(jac_default)).norm(), 0.0);
    EXPECT_EQ((Dense(curvature) - Dense(curvature_default)).norm(), 0.0);

    // Residual and Jacobian parts together, with other weights for the curvature.
    const Vec curvature_r = 3.0 * RandomVec(model.num_pairs(), 1.0, &rng);
    model.GapDerivatives(u, curvature_r, &jac_single, &curvature_single);
    Vec phi_both, reaction_both;
    SpMat jac_both, curvature_both;
    model.GapsReactionAndDerivatives(u, r, curvature_r, &phi_both, &reaction_both, &jac_both,
                                     &curvature_both);
    EXPECT_EQ((phi_both - phi).norm(), 0.0);
    EXPECT_EQ((reaction_both - reaction).norm(), 0.0);
    EXPECT_EQ((Dense(jac_both) - Dense(jac_single)).norm(), 0.0);
    EXPECT_EQ((Dense(curvature_both) - Dense(curvature_single)).norm(), 0.0);
    EXPECT_GT((Dense(curvature_both) - Dense(curvature)).norm(), 0.0);
  }
}

TEST(ModelTest, BodyContactPatternsIgnoreUAndR) {
  const BodyContactModel model = MakeTrussContact2D();
  std::mt19937 rng(23);
  const int d = model.num_dofs();
  const int nc = model.num_pairs();
  SpMat jac, curvature;
  model.GapJacobian(RandomVec(d, 0.2, &rng), &jac);
  model.GapCurvature(RandomVec(d, 0.2, &rng), Vec::Zero(nc), &curvature);
  const Eigen::Index jac_nnz = jac.nonZeros();
  const Eigen::Index curvature_nnz = curvature.nonZeros();
  // One entry per free component of each pair's node: the pinned node 0 has none, node 4 (y
  // supported) one, the other nodes two each.
  EXPECT_EQ(jac_nnz, 7 * 2 + 2 * 1);
  // Curvature blocks of pairs on curved obstacles only: nodes 5, 6, 7, 8, 3 (2 x 2 each) and
  // node 4 (x only, 1 x 1).
  EXPECT_EQ(curvature_nnz, 5 * 4 + 1);
  const Vec u = RandomVec(d, 0.2, &rng);
  const Vec r = -RandomVec(nc, 1.0, &rng).cwiseAbs();
  model.GapJacobian(u, &jac);
  model.GapCurvature(u, r, &curvature);
  EXPECT_EQ(jac.nonZeros(), jac_nnz);
  EXPECT_EQ(curvature.nonZeros(), curvature_nnz);
  SpMat fresh;
  model.GapCurvature(u, r, &fresh);
  EXPECT_EQ((Dense(curvature) - Dense(fresh)).norm(), 0.0);
}

TEST(ModelTest, BodyContactWithFlatObstaclesIsLinearWithEmptyCurvature) {
  // The P1 layout in miniature: a Q4 block against a wall x <= 0 and a floor y <= 0.
  const int n = 3;
  auto body = std::make_shared<PlaneStressQ4>(GridCoordinates(n, n, 2.0, 2.0, 0.0, nullptr),
                                              GridElements(n, n), kSteelish);
  std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<HalfSpace>(MakePoint({0.0, 0.0}), MakePoint({-1.0, 0.0})),
      std::make_shared<HalfSpace>(MakePoint({0.0, 0.0}), MakePoint({0.0, -1.0}))};
  std::vector<ContactPair> pairs;
  for (int j = 0; j <= n; ++j) pairs.push_back({j * (n + 1), 0});
  for (int i = 0; i <= n; ++i) pairs.push_back({i, 1});
  Vec load = Vec::Zero(body->num_dofs());
  for (int j = 0; j < n; ++j) {
    body->AddEdgeTraction(j * (n + 1) + n, (j + 1) * (n + 1) + n, MakePoint({-0.5, -0.5}), &load);
  }
  const BodyContactModel model(body, obstacles, pairs, load);
  EXPECT_TRUE(model.is_linear());
  EXPECT_EQ(model.num_pairs(), 2 * (n + 1));
  const Vec u = Vec::LinSpaced(model.num_dofs(), -0.1, 0.1);
  SpMat curvature;
  model.GapCurvature(u, Vec::Constant(model.num_pairs(), -1.0), &curvature);
  EXPECT_EQ(curvature.rows(), model.num_dofs());
  EXPECT_EQ(curvature.cols(), model.num_dofs());
  EXPECT_EQ(curvature.nonZeros(), 0);
  // Affine gaps: phi = -(X + u) . e on the wall pairs.
  Vec phi;
  model.Gaps(u, &phi);
  EXPECT_DOUBLE_EQ(phi[1], -(body->reference(n + 1)[0] + u[2 * (n + 1)]));
  SpMat jac;
  model.GapJacobian(u, &jac);
  // A wall's constant normal reaches one of its node's two dofs: one entry per pair.
  EXPECT_EQ(jac.nonZeros(), model.num_pairs());
  EXPECT_DOUBLE_EQ(jac.coeff(1, 2 * (n + 1)), -1.0);
  EXPECT_NEAR(model.load_pattern().sum(), -0.5 * kSteelish.thickness * 2.0 * 2.0, 1e-15);

  // The same body against a curved obstacle is not linear.
  const BodyContactModel curved(
      body, {std::make_shared<Ball>(MakePoint({1.0, -5.0}), 5.0, Ball::Side::kSolid)}, {{1, 0}},
      load);
  EXPECT_FALSE(curved.is_linear());
}

TEST(ModelTest, BodyContactRejectsInvalidInput) {
  auto truss = MakeTruss2D();
  const Vec load = Vec::Zero(truss->num_dofs());
  const std::vector<std::shared_ptr<const Obstacle>> obstacles = {
      std::make_shared<HalfSpace>(MakePoint({0.0, 0.0}), MakePoint({0.0, -1.0}))};
  ExpectInvalid(
      [&] {
        BodyContactModel(truss, obstacles, {{0, 0}, {9, 0}}, load);
      },
      "pair 1 names unknown node 9");
  ExpectInvalid(
      [&] {
        BodyContactModel(truss, obstacles, {{0, 0}, {1, 0}, {2, 1}}, load);
      },
      "pair 2 names unknown obstacle 1");
  ExpectInvalid(
      [&] {
        BodyContactModel(
            truss,
            {std::make_shared<HalfSpace>(MakePoint({0.0, 0.0, 0.0}), MakePoint({0.0, 0.0, 1.0}))},
            {{0, 0}}, load);
      },
      "dimension 3");
  ExpectInvalid(
      [&] {
        BodyContactModel(truss, obstacles, {{0, 0}}, Vec::Zero(3));
      },
      "load pattern");
  ExpectInvalid([&] { BodyContactModel(nullptr, obstacles, {}, load); }, "null");
  const BodyContactModel model(truss, obstacles, {{1, 0}}, load);
  Vec phi;
  ExpectInvalid([&] { model.Gaps(Vec::Zero(2), &phi); }, "size");
  SpMat m;
  ExpectInvalid([&] { model.GapCurvature(load, Vec::Zero(2), &m); }, "r has size");
}

}  // namespace
}  // namespace cb
