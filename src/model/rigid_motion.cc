#include "model/rigid_motion.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>

namespace cb {
namespace {

// Ranks below this (relative to the largest pivot) count as zero; the modes are scaled to O(1)
// so that it does not depend on the body's size.
constexpr double kRankThreshold = 1e-9;

// The rigid-body modes of the reference configuration, one column each (translations first,
// then rotations about the centroid), scaled so that the body's extent is 1.
Mat RigidBodyModes(const ElasticBody& body) {
  const int dim = body.dim();
  const int n = body.num_nodes();
  const int m = dim == 2 ? 3 : 6;
  Point centre = Point::Zero(dim);
  for (int i = 0; i < n; ++i) centre += body.reference(i);
  centre /= n;
  double size = 0.0;
  for (int i = 0; i < n; ++i) size = std::max(size, (body.reference(i) - centre).norm());
  if (!(size > 0.0)) size = 1.0;
  Mat modes = Mat::Zero(static_cast<Eigen::Index>(n) * dim, m);
  for (int i = 0; i < n; ++i) {
    const Point x = (body.reference(i) - centre) / size;
    for (int c = 0; c < dim; ++c) modes(i * dim + c, c) = 1.0;
    if (dim == 2) {
      modes(i * 2, 2) = -x[1];
      modes(i * 2 + 1, 2) = x[0];
    } else {
      for (int a = 0; a < 3; ++a) {  // e_a x (x - centre)
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        axis[a] = 1.0;
        const Eigen::Vector3d w = axis.cross(Eigen::Vector3d(x[0], x[1], x[2]));
        for (int c = 0; c < 3; ++c) modes(i * 3 + c, 3 + a) = w[c];
      }
    }
  }
  return modes;
}

// The constraint rows on the modes: a supported component moves with its row of the modes, a
// pair with its obstacle's unit normal applied to its node's rows.
std::vector<Eigen::RowVectorXd> ConstraintRows(
    const ElasticBody& body, const Mat& modes,
    const std::vector<std::shared_ptr<const Obstacle>>& obstacles,
    const std::vector<ContactPair>& pairs) {
  const int dim = body.dim();
  std::vector<Eigen::RowVectorXd> rows;
  for (int i = 0; i < body.num_nodes(); ++i) {
    for (int c = 0; c < dim; ++c) {
      if (body.dofs().dof(i, c) < 0) rows.push_back(modes.row(i * dim + c));
    }
  }
  for (const ContactPair& p : pairs) {
    const Point x = body.reference(p.node);
    Point normal = obstacles[p.obstacle]->Gradient(x);
    if (!(normal.norm() > 0.0)) continue;
    normal.normalize();
    rows.push_back(normal.transpose() * modes.block(p.node * dim, 0, dim, modes.cols()));
  }
  return rows;
}

// Names one motion of `free` (coefficients of the modes): a rotation if it has any (a rotation
// about another point mixes in translations, which would be the wrong name), else the dominant
// translation.
std::string NameOfMotion(int dim, const Vec& free) {
  const int m = static_cast<int>(free.size());
  const int rotations = dim == 2 ? 1 : 3;
  Eigen::Index largest = 0;
  if (free.tail(rotations).cwiseAbs().maxCoeff(&largest) > 1e-6 * free.norm()) {
    largest += m - rotations;
  } else {
    free.head(dim).cwiseAbs().maxCoeff(&largest);
  }
  static const char* const kModes2[3] = {"translation in x", "translation in y",
                                         "rotation about z"};
  static const char* const kModes3[6] = {"translation in x", "translation in y",
                                         "translation in z", "rotation about x",
                                         "rotation about y", "rotation about z"};
  return dim == 2 ? kModes2[largest] : kModes3[largest];
}

void CheckPairs(const ElasticBody& body,
                const std::vector<std::shared_ptr<const Obstacle>>& obstacles,
                const std::vector<ContactPair>& pairs) {
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const ContactPair& p = pairs[k];
    if (p.node < 0 || p.node >= body.num_nodes()) {
      throw std::invalid_argument("CheckRigidMotionRestraint: pairs[" + std::to_string(k) +
                                  "].node " + std::to_string(p.node) + " is not a node");
    }
    if (p.obstacle < 0 || p.obstacle >= static_cast<int>(obstacles.size()) ||
        obstacles[p.obstacle] == nullptr) {
      throw std::invalid_argument("CheckRigidMotionRestraint: pairs[" + std::to_string(k) +
                                  "].obstacle " + std::to_string(p.obstacle) +
                                  " is not an obstacle");
    }
  }
}

}  // namespace

RigidMotionRestraint CheckRigidMotionRestraint(
    const ElasticBody& body, const std::vector<std::shared_ptr<const Obstacle>>& obstacles,
    const std::vector<ContactPair>& pairs) {
  CheckPairs(body, obstacles, pairs);
  const Mat modes = RigidBodyModes(body);
  const int m = static_cast<int>(modes.cols());
  RigidMotionRestraint restraint;
  Eigen::FullPivLU<Mat> all(modes);
  all.setThreshold(kRankThreshold);
  restraint.modes = static_cast<int>(all.rank());

  const std::vector<Eigen::RowVectorXd> rows = ConstraintRows(body, modes, obstacles, pairs);
  restraint.constraints = static_cast<int>(rows.size());
  if (rows.empty()) {
    // Every motion is free; the first mode names one.
    restraint.free_example = NameOfMotion(body.dim(), Vec::Unit(m, 0));
    return restraint;
  }
  Mat constraints(static_cast<Eigen::Index>(rows.size()), m);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    constraints.row(static_cast<Eigen::Index>(k)) = rows[k];
  }
  Eigen::FullPivLU<Mat> held(constraints);
  held.setThreshold(kRankThreshold);
  restraint.restrained = static_cast<int>(held.rank());
  if (restraint.restrained < restraint.modes) {
    restraint.free_example = NameOfMotion(body.dim(), held.kernel().col(0));
  }
  return restraint;
}

}  // namespace cb
