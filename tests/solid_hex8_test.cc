// The eight-node hexahedral solid (small and large deformation) and the structured box mesh:
// derivatives against finite differences, the 3-D patch test, rigid-body motions, consistent
// face tractions.
#include "model/solid_hex8.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "elastic_body_check.h"
#include "problems/box_mesh.h"
#include "refusal.h"

namespace cb {
namespace {

constexpr double kFdTol = 1e-6;
const SolidMaterial kMaterial{200.0, 0.3};

Vec RandomVec(int n, double scale, std::mt19937* rng) {
  std::uniform_real_distribution<double> dist(-scale, scale);
  Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = dist(*rng);
  return v;
}

// A box mesh whose interior nodes are moved at random by up to `jitter` of a cell: the
// boundary faces stay planar, the elements are general hexahedra.
BoxMesh DistortedBox(const std::array<int, 3>& cells, double jitter, std::mt19937* rng) {
  BoxMesh mesh = MakeBoxMesh({cells, {2.0, 1.5, 1.0}, {1.0, 1.0, 1.0}});
  std::uniform_real_distribution<double> dist(-jitter, jitter);
  for (int k = 1; k < cells[2]; ++k) {
    for (int j = 1; j < cells[1]; ++j) {
      for (int i = 1; i < cells[0]; ++i) {
        auto row = mesh.coordinates.row(mesh.node(i, j, k));
        row[0] += dist(*rng) * 2.0 / cells[0];
        row[1] += dist(*rng) * 1.5 / cells[1];
        row[2] += dist(*rng) * 1.0 / cells[2];
      }
    }
  }
  return mesh;
}

// `statement` throws std::invalid_argument naming each of `names` (the input at fault and the
// bad value; tests/refusal.h).
template <typename F>
void ExpectInvalid(F&& statement, const std::vector<std::string>& names) {
  try {
    statement();
    ADD_FAILURE() << "expected std::invalid_argument naming " << names.front();
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(cb::testing_support::Names(e.what(), names));
  }
}

TEST(SolidHex8Test, SmallStrainDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(11);
  const BoxMesh mesh = DistortedBox({3, 2, 2}, 0.2, &rng);
  std::vector<bool> fixed(3 * mesh.coordinates.rows(), false);
  fixed[0] = fixed[1] = fixed[2] = true;
  const SolidHex8 body(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kSmallStrain,
                       fixed);
  EXPECT_TRUE(body.is_linear());
  fd_check::ExpectBodyDerivativesMatch(body, RandomVec(body.num_dofs(), 0.05, &rng), kFdTol);
}

TEST(SolidHex8Test, LargeStrainDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(12);
  const BoxMesh mesh = DistortedBox({3, 2, 2}, 0.2, &rng);
  std::vector<bool> fixed(3 * mesh.coordinates.rows(), false);
  fixed[4] = true;
  const SolidHex8 body(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kLargeStrain,
                       fixed);
  EXPECT_FALSE(body.is_linear());
  // Strains of some 10 %: well inside the non-linear range of the law.
  fd_check::ExpectBodyDerivativesMatch(body, RandomVec(body.num_dofs(), 0.05, &rng), kFdTol);
}

TEST(SolidHex8Test, LargeStrainTangentAtRestIsTheLinearStiffness) {
  std::mt19937 rng(13);
  const BoxMesh mesh = DistortedBox({2, 2, 2}, 0.2, &rng);
  const SolidHex8 small(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kSmallStrain);
  const SolidHex8 large(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kLargeStrain);
  SpMat ks, kl;
  const Vec zero = Vec::Zero(small.num_dofs());
  small.Stiffness(zero, &ks);
  large.Stiffness(zero, &kl);
  EXPECT_LT((Mat(ks) - Mat(kl)).cwiseAbs().maxCoeff(), 1e-12 * Mat(ks).cwiseAbs().maxCoeff());
  EXPECT_EQ(large.Energy(zero), 0.0);
}

// A linear field u = A X + c: constant strain, so K u equals the consistent face loads of the
// constant stress (interior nodes: zero) and the energy is volume eps:sigma / 2.
TEST(SolidHex8Test, PatchTestLinearFieldGivesExactStressResultants) {
  std::mt19937 rng(14);
  const std::array<int, 3> cells = {3, 3, 2};
  const BoxMesh mesh = DistortedBox(cells, 0.25, &rng);
  const SolidHex8 body(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kSmallStrain);
  Eigen::Matrix3d a;
  a << 1e-3, -4e-4, 2e-4, 7e-4, -2e-3, 5e-4, -3e-4, 1e-4, 6e-4;
  const Eigen::Vector3d c(0.3, -0.1, 0.2);
  Vec u(body.num_dofs());
  for (int n = 0; n < body.num_nodes(); ++n) {
    u.segment<3>(3 * n) = a * mesh.coordinates.row(n).transpose() + c;
  }
  const double nu = kMaterial.poisson_ratio, e = kMaterial.youngs_modulus;
  const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
  const Eigen::Matrix3d eps = 0.5 * (a + a.transpose());
  const Eigen::Matrix3d sigma = lambda * eps.trace() * Eigen::Matrix3d::Identity() + 2 * mu * eps;
  Vec expected = Vec::Zero(body.num_dofs());
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      normal[axis] = side == 0 ? -1.0 : 1.0;
      const Point traction = sigma * normal;
      for (const auto& face : mesh.Faces(axis, side == 0 ? 0 : cells[axis])) {
        body.AddFaceTraction(face, traction, &expected);
      }
    }
  }
  Vec f;
  body.InternalForce(u, &f);
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 0.0);
  EXPECT_LT((f - expected).cwiseAbs().maxCoeff(), 1e-10 * scale);
  const double volume = 2.0 * 1.5 * 1.0;
  const double exact = 0.5 * volume * (eps.array() * sigma.array()).sum();
  EXPECT_NEAR(body.Energy(u), exact, 1e-9 * exact);
  // The stress measure of every cell is the von Mises stress of sigma.
  const Eigen::Matrix3d dev = sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity();
  const double von_mises = std::sqrt(1.5 * dev.squaredNorm());
  for (double s : body.VonMisesStress(u)) EXPECT_NEAR(s, von_mises, 1e-9 * von_mises);
  // The output fields: von_mises_stress, and the tensor `stress` (9 components, row by row)
  // sigma itself in every cell.
  const std::vector<CellField> fields = body.CellFields(u);
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(fields[0].name, "von_mises_stress");
  EXPECT_EQ(fields[1].name, "stress");
  ASSERT_EQ(fields[1].components, 9);
  ASSERT_EQ(fields[1].values.size(), 9 * body.Cells().size());
  const double largest = sigma.cwiseAbs().maxCoeff();
  for (std::size_t k = 0; k < fields[1].values.size(); ++k) {
    const int i = static_cast<int>(k % 9) / 3, j = static_cast<int>(k % 3);
    EXPECT_NEAR(fields[1].values[k], sigma(i, j), 1e-9 * largest) << k;
  }
}

// The large-deformation patch test: a homogeneous deformation x = F X reproduces the constant
// first Piola-Kirchhoff stress (interior nodes free of force) and the energy volume W(F).
TEST(SolidHex8Test, LargeStrainHomogeneousDeformationIsReproduced) {
  std::mt19937 rng(15);
  const std::array<int, 3> cells = {2, 3, 2};
  const BoxMesh mesh = DistortedBox(cells, 0.25, &rng);
  const SolidHex8 body(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kLargeStrain);
  Eigen::Matrix3d f;
  f << 1.2, 0.1, -0.05, 0.0, 0.9, 0.2, 0.1, -0.1, 1.1;
  Vec u(body.num_dofs());
  for (int n = 0; n < body.num_nodes(); ++n) {
    const Eigen::Vector3d x = mesh.coordinates.row(n).transpose();
    u.segment<3>(3 * n) = f * x - x;
  }
  const double nu = kMaterial.poisson_ratio, e = kMaterial.youngs_modulus;
  const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
  const double log_j = std::log(f.determinant());
  const double w = 0.5 * mu * (f.squaredNorm() - 3) - mu * log_j + 0.5 * lambda * log_j * log_j;
  EXPECT_NEAR(body.Energy(u), 3.0 * w, 1e-12 * 3.0 * w);
  const Eigen::Matrix3d p =
      mu * (f - f.inverse().transpose()) + lambda * log_j * f.inverse().transpose();
  Vec expected = Vec::Zero(body.num_dofs());
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      normal[axis] = side == 0 ? -1.0 : 1.0;
      for (const auto& face : mesh.Faces(axis, side == 0 ? 0 : cells[axis])) {
        body.AddFaceTraction(face, p * normal, &expected);
      }
    }
  }
  Vec force;
  body.InternalForce(u, &force);
  EXPECT_LT((force - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
}

TEST(SolidHex8Test, RigidMotionsCarryNoForce) {
  std::mt19937 rng(16);
  const BoxMesh mesh = DistortedBox({3, 2, 2}, 0.2, &rng);
  const SolidHex8 small(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kSmallStrain);
  const SolidHex8 large(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kLargeStrain);
  SpMat stiffness;
  small.Stiffness(Vec::Zero(small.num_dofs()), &stiffness);
  const Eigen::SelfAdjointEigenSolver<Mat> eig{Mat(stiffness)};
  const double top = eig.eigenvalues().maxCoeff();
  // Exactly six zero-energy modes (three translations, three rotations); 2 x 2 x 2 Gauss
  // leaves no spurious (hourglass) mode.
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * top);
  EXPECT_LT(std::abs(eig.eigenvalues()[5]), 1e-11 * top);
  EXPECT_GT(eig.eigenvalues()[6], 1e-6 * top);
  // Small deformation: translations and infinitesimal rotations u = w x X.
  for (int mode = 0; mode < 6; ++mode) {
    Vec u(small.num_dofs());
    for (int n = 0; n < small.num_nodes(); ++n) {
      const Eigen::Vector3d x = mesh.coordinates.row(n).transpose();
      Eigen::Vector3d axis = Eigen::Vector3d::Zero();
      axis[mode % 3] = 1.0;
      u.segment<3>(3 * n) = mode < 3 ? axis : Eigen::Vector3d(axis.cross(x));
    }
    Vec f;
    small.InternalForce(u, &f);
    EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-12 * top);
  }
  // Large deformation: a finite rotation (60 degrees) plus a translation: no energy, no force.
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(std::acos(0.5), Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Vec u(large.num_dofs());
  for (int n = 0; n < large.num_nodes(); ++n) {
    const Eigen::Vector3d x = mesh.coordinates.row(n).transpose();
    u.segment<3>(3 * n) = r * x - x + Eigen::Vector3d(0.5, -1.0, 2.0);
  }
  EXPECT_LT(std::abs(large.Energy(u)), 1e-12 * top);
  Vec f;
  large.InternalForce(u, &f);
  EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-11 * top);
}

TEST(SolidHex8Test, InvertedElementHasInfiniteEnergy) {
  const BoxMesh mesh = MakeBoxMesh({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}});
  const SolidHex8 body(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kLargeStrain);
  Vec u = Vec::Zero(body.num_dofs());
  for (int n = 4; n < 8; ++n) u[3 * n + 2] = -2.0;  // the top face pushed through the bottom
  EXPECT_EQ(body.Energy(u), std::numeric_limits<double>::infinity());
  Vec f;
  body.InternalForce(u, &f);
  EXPECT_FALSE(f.allFinite());
}

TEST(SolidHex8Test, FaceTractionIntegratesToTractionTimesArea) {
  // A face of a graded mesh and a skewed (non-planar) one: the nodal forces sum to t times the
  // area, and on a rectangle each node gets a quarter.
  const BoxMesh mesh = MakeBoxMesh({{2, 3, 1}, {2.0, 3.0, 1.0}, {1.5, 1.0, 1.0}});
  const SolidHex8 body(mesh.coordinates, mesh.elements, kMaterial, SolidKinematics::kSmallStrain);
  Vec load = Vec::Zero(body.num_dofs());
  Point t(3);
  t << 1.0, -2.0, 3.0;
  for (const auto& face : mesh.Faces(2, 1)) body.AddFaceTraction(face, t, &load);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int n = 0; n < body.num_nodes(); ++n) total += load.segment<3>(3 * n);
  EXPECT_LT((total - 6.0 * Eigen::Vector3d(t)).norm(), 1e-13);
  Vec one = Vec::Zero(body.num_dofs());
  const auto face = mesh.Faces(2, 1).front();
  body.AddFaceTraction(face, t, &one);
  const double area = mesh.coordinates(face[1], 0) * 1.0;  // first cell: width x 1
  EXPECT_NEAR(one[3 * face[0]], 0.25 * area * t[0], 1e-14);
}

TEST(SolidHex8Test, BoxMeshIsGradedTowardTheOrigin) {
  const BoxMesh mesh = MakeBoxMesh({{4, 2, 3}, {4.0, 2.0, 3.0}, {2.0, 1.0, 1.0}});
  EXPECT_EQ(mesh.coordinates.rows(), 5 * 3 * 4);
  EXPECT_EQ(mesh.elements.size(), 24u);
  EXPECT_DOUBLE_EQ(mesh.coordinates(mesh.node(1, 0, 0), 0), 4.0 / 16.0);
  EXPECT_DOUBLE_EQ(mesh.coordinates(mesh.node(4, 2, 3), 2), 3.0);
  EXPECT_EQ(mesh.FaceNodes(1, 2).size(), 20u);
  EXPECT_EQ(mesh.Faces(0, 4).size(), 6u);
  ExpectInvalid([] { MakeBoxMesh({{0, 1, 1}, {1, 1, 1}, {1, 1, 1}}); }, {"cells", "x", "got 0"});
  ExpectInvalid([] { MakeBoxMesh({{1, 1, 1}, {1, -1, 1}, {1, 1, 1}}); }, {"size", "y", "got -1"});
  ExpectInvalid(
      [] {
        MakeBoxMesh({{1, 1, 1}, {1, 1, 1}, {1, 1, 0.5}});
      },
      {"grading", "z", "got 0.5"});
  ExpectInvalid([&] { mesh.Faces(0, 2); }, {"side 2", "axis 0"});
}

TEST(SolidHex8Test, RejectsInvalidInput) {
  const BoxMesh mesh = MakeBoxMesh({{2, 1, 1}, {2, 1, 1}, {1, 1, 1}});
  const auto kinematics = SolidKinematics::kSmallStrain;
  auto elements = mesh.elements;
  std::swap(elements[1][0], elements[1][4]);
  ExpectInvalid([&] { SolidHex8(mesh.coordinates, elements, kMaterial, kinematics); },
                {"element 1", "Jacobian"});
  elements = mesh.elements;
  elements[0][3] = 99;
  ExpectInvalid([&] { SolidHex8(mesh.coordinates, elements, kMaterial, kinematics); },
                {"element 0", "node 99"});
  elements[0][3] = elements[0][2];
  ExpectInvalid([&] { SolidHex8(mesh.coordinates, elements, kMaterial, kinematics); },
                {"element 0", "node " + std::to_string(elements[0][2])});
  ExpectInvalid(
      [&] {
        SolidHex8(mesh.coordinates, mesh.elements, {0.0, 0.3}, kinematics);
      },
      {"Young", "got 0"});
  ExpectInvalid(
      [&] {
        SolidHex8(mesh.coordinates, mesh.elements, {1.0, 0.5}, kinematics);
      },
      {"Poisson", "got 0.5"});
  ExpectInvalid([&] { SolidHex8(Mat::Zero(12, 2), mesh.elements, kMaterial, kinematics); },
                {"coordinates", "2"});
  ExpectInvalid([&] { SolidHex8(mesh.coordinates, mesh.elements, kMaterial, kinematics, {true}); },
                {"`fixed`", "1"});
  const SolidHex8 body(mesh.coordinates, mesh.elements, kMaterial, kinematics);
  Vec load = Vec::Zero(body.num_dofs());
  ExpectInvalid(
      [&] {
        body.AddFaceTraction({0, 1, 2, 77}, Point::Zero(3), &load);
      },
      {"AddFaceTraction", "node 77"});
  ExpectInvalid(
      [&] {
        body.AddFaceTraction({0, 1, 2, 3}, Point::Zero(2), &load);
      },
      {"AddFaceTraction", "2"});
  ExpectInvalid([&] { body.Energy(Vec::Zero(3)); }, {"Energy", "size 3"});
}

}  // namespace
}  // namespace cb
