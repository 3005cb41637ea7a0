#include "model/body_contact_model.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace cb {
namespace {

[[noreturn]] void ThrowPair(std::size_t pair, const std::string& reason) {
  throw std::invalid_argument("BodyContactModel: pair " + std::to_string(pair) + " " + reason);
}

void CheckSize(const Vec& v, Eigen::Index size, const char* what, const char* name) {
  if (v.size() != size) {
    throw std::invalid_argument(std::string("BodyContactModel::") + what + ": " + name +
                                " has size " + std::to_string(v.size()) + ", expected " +
                                std::to_string(size));
  }
}

}  // namespace

BodyContactModel::BodyContactModel(std::shared_ptr<const ElasticBody> body,
                                   std::vector<std::shared_ptr<const Obstacle>> obstacles,
                                   std::vector<ContactPair> pairs, Vec load_pattern)
    : body_(std::move(body)),
      obstacles_(std::move(obstacles)),
      pairs_(std::move(pairs)),
      load_(std::move(load_pattern)) {
  if (body_ == nullptr) throw std::invalid_argument("BodyContactModel: the body is null");
  const int dim = body_->dim();
  for (std::size_t k = 0; k < obstacles_.size(); ++k) {
    if (obstacles_[k] == nullptr) {
      throw std::invalid_argument("BodyContactModel: obstacle " + std::to_string(k) + " is null");
    }
    if (obstacles_[k]->dim() != dim) {
      throw std::invalid_argument("BodyContactModel: obstacle " + std::to_string(k) + " (" +
                                  obstacles_[k]->Describe() + ") has dimension " +
                                  std::to_string(obstacles_[k]->dim()) + " but the body has " +
                                  std::to_string(dim));
    }
  }
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const ContactPair& pair = pairs_[p];
    if (pair.node < 0 || pair.node >= body_->num_nodes()) {
      ThrowPair(p, "names unknown node " + std::to_string(pair.node) + " (the body has " +
                       std::to_string(body_->num_nodes()) + " nodes)");
    }
    if (pair.obstacle < 0 || pair.obstacle >= static_cast<int>(obstacles_.size())) {
      ThrowPair(p, "names unknown obstacle " + std::to_string(pair.obstacle) + " (there are " +
                       std::to_string(obstacles_.size()) + ")");
    }
  }
  const int d = body_->num_dofs();
  if (load_.size() != d) {
    throw std::invalid_argument("BodyContactModel: the load pattern has size " +
                                std::to_string(load_.size()) +
                                ", expected d = " + std::to_string(d));
  }

  // Both patterns are fixed here, in the order GapJacobian / GapCurvature add to them: they
  // depend on the pairs and the supports only, never on u or r.
  const DofMap& map = body_->dofs();
  std::vector<ScatterPattern::Entry> jacobian_entries;
  std::vector<ScatterPattern::Entry> curvature_entries;
  jacobian_entries.reserve(pairs_.size() * dim);
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const ContactPair& pair = pairs_[p];
    pair_reference_.push_back(body_->reference(pair.node));
    std::array<int, 3> dofs = {-1, -1, -1};
    for (int c = 0; c < dim; ++c) {
      dofs[c] = map.dof(pair.node, c);
      if (dofs[c] >= 0) jacobian_entries.emplace_back(static_cast<int>(p), dofs[c]);
    }
    pair_dofs_.push_back(dofs);
    if (!obstacles_[pair.obstacle]->is_curved()) continue;
    curved_pairs_.push_back(static_cast<int>(p));
    for (int b = 0; b < dim; ++b) {
      const int col = map.dof(pair.node, b);
      if (col < 0) continue;
      for (int a = 0; a < dim; ++a) {
        const int row = map.dof(pair.node, a);
        if (row >= 0) curvature_entries.emplace_back(row, col);
      }
    }
  }
  jacobian_pattern_ = ScatterPattern(num_pairs(), d, jacobian_entries);
  curvature_pattern_ = ScatterPattern(d, d, curvature_entries);
}

bool BodyContactModel::is_linear() const {
  if (!body_->is_linear()) return false;
  for (const ContactPair& pair : pairs_) {
    if (obstacles_[pair.obstacle]->is_curved()) return false;
  }
  return true;
}

Point BodyContactModel::PairPosition(int p, const Vec& u) const {
  Point x = pair_reference_[p];
  const std::array<int, 3>& dofs = pair_dofs_[p];
  for (int c = 0; c < x.size(); ++c) {
    if (dofs[c] >= 0) x[c] += u[dofs[c]];
  }
  return x;
}

void BodyContactModel::Gaps(const Vec& u, Vec* phi) const {
  CheckSize(u, num_dofs(), "Gaps", "u");
  phi->resize(num_pairs());
  for (int p = 0; p < num_pairs(); ++p) {
    (*phi)[p] = obstacles_[pairs_[p].obstacle]->Value(PairPosition(p, u));
  }
}

void BodyContactModel::GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const {
  CheckSize(u, num_dofs(), "GeneralisedReaction", "u");
  CheckSize(r, num_pairs(), "GeneralisedReaction", "r");
  reaction->setZero(num_dofs());
  for (int p = 0; p < num_pairs(); ++p) {
    const Point grad = obstacles_[pairs_[p].obstacle]->Gradient(PairPosition(p, u));
    const std::array<int, 3>& dofs = pair_dofs_[p];
    for (int c = 0; c < grad.size(); ++c) {
      if (dofs[c] >= 0) (*reaction)[dofs[c]] += grad[c] * r[p];
    }
  }
}

// Row p of grad phi: d varphi(X + u_node) / d u = grad varphi on the node's free components
// (the position depends on u with unit slope there and not at all on supported components).
void BodyContactModel::GapJacobian(const Vec& u, SpMat* jacobian) const {
  CheckSize(u, num_dofs(), "GapJacobian", "u");
  jacobian_pattern_.Reset(jacobian);
  double* values = jacobian->valuePtr();
  const std::vector<int>& slots = jacobian_pattern_.slots();
  std::size_t next = 0;
  for (int p = 0; p < num_pairs(); ++p) {
    const Point grad = obstacles_[pairs_[p].obstacle]->Gradient(PairPosition(p, u));
    const std::array<int, 3>& dofs = pair_dofs_[p];
    for (int c = 0; c < grad.size(); ++c) {
      if (dofs[c] >= 0) values[slots[next++]] += grad[c];
    }
  }
}

// sum_p r_p hess phi_p(u): the node's free-dof block of r_p hess varphi for curved obstacles,
// the curvature term of dF1/ddu in (29).
void BodyContactModel::GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const {
  CheckSize(u, num_dofs(), "GapCurvature", "u");
  CheckSize(r, num_pairs(), "GapCurvature", "r");
  curvature_pattern_.Reset(curvature);
  double* values = curvature->valuePtr();
  const int dim = body_->dim();
  const std::vector<int>& slots = curvature_pattern_.slots();
  std::size_t next = 0;
  for (int p : curved_pairs_) {
    const PointMat hess = obstacles_[pairs_[p].obstacle]->Hessian(PairPosition(p, u));
    const std::array<int, 3>& dofs = pair_dofs_[p];
    for (int b = 0; b < dim; ++b) {
      if (dofs[b] < 0) continue;
      for (int a = 0; a < dim; ++a) {
        if (dofs[a] < 0) continue;
        values[slots[next++]] += r[p] * hess(a, b);
      }
    }
  }
}

}  // namespace cb
