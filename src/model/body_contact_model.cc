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
  const Vec zero = Vec::Zero(d);
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const ContactPair& pair = pairs_[p];
    pair_reference_.push_back(body_->reference(pair.node));
    std::array<int, 3> dofs = {-1, -1, -1};
    for (int c = 0; c < dim; ++c) dofs[c] = map.dof(pair.node, c);
    pair_dofs_.push_back(dofs);
    const bool curved = obstacles_[pair.obstacle]->is_curved();
    ObstacleLocal flat;  // a flat obstacle's gradient is its normal, the same everywhere
    if (!curved) EvaluatePair(static_cast<int>(p), zero, Obstacle::Order::kGradient, &flat);
    std::array<bool, 3> entry = {false, false, false};
    for (int c = 0; c < dim; ++c) {
      entry[c] = dofs[c] >= 0 && (curved || flat.gradient[c] != 0.0);
      if (entry[c]) jacobian_entries.emplace_back(static_cast<int>(p), dofs[c]);
    }
    pair_gradient_entry_.push_back(entry);
    if (!curved) continue;
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

bool BodyContactModel::has_constant_stiffness() const { return body_->is_linear(); }

bool BodyContactModel::is_linear() const {
  if (!body_->is_linear()) return false;
  for (const ContactPair& pair : pairs_) {
    if (obstacles_[pair.obstacle]->is_curved()) return false;
  }
  return true;
}

void BodyContactModel::EvaluatePair(int p, const Vec& u, Obstacle::Order order,
                                    ObstacleLocal* local) const {
  double x[3];
  const Point& reference = pair_reference_[p];
  const std::array<int, 3>& dofs = pair_dofs_[p];
  for (int c = 0; c < reference.size(); ++c)
    x[c] = reference[c] + (dofs[c] >= 0 ? u[dofs[c]] : 0.0);
  obstacles_[pairs_[p].obstacle]->Evaluate(x, order, local);
}

// One pass over the pairs, one obstacle evaluation each, filling the outputs that are not null:
// phi_p; the generalised reaction grad phi^T r of (9); row p of grad phi, d varphi(X + u_node) /
// d u = grad varphi on the node's free components (the position depends on u with unit slope
// there and not at all on supported components); and sum_p r_p hess phi_p(u) with the weights
// curvature_r: the node's free-dof block of r_p hess varphi for curved obstacles, the curvature
// term of dF1/ddu in (29). Both matrix patterns were fixed by the constructor; the pairs are
// visited in that order.
void BodyContactModel::EvaluatePairs(const char* what, const Vec& u, const PairOutputs& out) const {
  CheckSize(u, num_dofs(), what, "u");
  if (out.r != nullptr) CheckSize(*out.r, num_pairs(), what, "r");
  if (out.curvature_r != nullptr) CheckSize(*out.curvature_r, num_pairs(), what, "r");
  if (out.phi != nullptr) out.phi->resize(num_pairs());
  if (out.reaction != nullptr) out.reaction->setZero(num_dofs());
  const int dim = body_->dim();
  double* jacobian_values = nullptr;
  double* curvature_values = nullptr;
  if (out.jacobian != nullptr) {
    jacobian_pattern_.Reset(out.jacobian);
    jacobian_values = out.jacobian->valuePtr();
  }
  if (out.curvature != nullptr) {
    curvature_pattern_.Reset(out.curvature);
    curvature_values = out.curvature->valuePtr();
  }
  const bool needs_gradient = out.reaction != nullptr || out.jacobian != nullptr;
  const int* jacobian_slots = jacobian_pattern_.slots().data();
  const int* curvature_slots = curvature_pattern_.slots().data();
  std::size_t next_jacobian = 0, next_curvature = 0;
  ObstacleLocal local;
  for (int p = 0; p < num_pairs(); ++p) {
    const bool curved = obstacles_[pairs_[p].obstacle]->is_curved();
    const bool with_curvature = curved && out.curvature != nullptr;
    if (out.phi == nullptr && !needs_gradient && !with_curvature) continue;
    EvaluatePair(p, u,
                 with_curvature   ? Obstacle::Order::kHessian
                 : needs_gradient ? Obstacle::Order::kGradient
                                  : Obstacle::Order::kValue,
                 &local);
    if (out.phi != nullptr) (*out.phi)[p] = local.value;
    const std::array<int, 3>& dofs = pair_dofs_[p];
    if (out.reaction != nullptr) {
      for (int c = 0; c < dim; ++c) {
        if (dofs[c] >= 0) (*out.reaction)[dofs[c]] += local.gradient[c] * (*out.r)[p];
      }
    }
    if (out.jacobian != nullptr) {
      for (int c = 0; c < dim; ++c) {
        if (pair_gradient_entry_[p][c]) {
          jacobian_values[jacobian_slots[next_jacobian++]] += local.gradient[c];
        }
      }
    }
    if (!with_curvature) continue;
    const double rp = (*out.curvature_r)[p];
    for (int b = 0; b < dim; ++b) {
      if (dofs[b] < 0) continue;
      for (int a = 0; a < dim; ++a) {
        if (dofs[a] < 0) continue;
        curvature_values[curvature_slots[next_curvature++]] += rp * local.hessian[a][b];
      }
    }
  }
}

void BodyContactModel::Gaps(const Vec& u, Vec* phi) const {
  EvaluatePairs("Gaps", u, {.phi = phi});
}

void BodyContactModel::GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const {
  EvaluatePairs("GeneralisedReaction", u, {.r = &r, .reaction = reaction});
}

void BodyContactModel::GapsAndReaction(const Vec& u, const Vec& r, Vec* phi, Vec* reaction) const {
  EvaluatePairs("GapsAndReaction", u, {.r = &r, .phi = phi, .reaction = reaction});
}

void BodyContactModel::GapJacobian(const Vec& u, SpMat* jacobian) const {
  EvaluatePairs("GapJacobian", u, {.jacobian = jacobian});
}

void BodyContactModel::GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const {
  EvaluatePairs("GapCurvature", u, {.curvature_r = &r, .curvature = curvature});
}

void BodyContactModel::GapDerivatives(const Vec& u, const Vec& r, SpMat* jacobian,
                                      SpMat* curvature) const {
  EvaluatePairs("GapDerivatives", u,
                {.curvature_r = &r, .jacobian = jacobian, .curvature = curvature});
}

void BodyContactModel::GapsReactionAndDerivatives(const Vec& u, const Vec& r,
                                                  const Vec& curvature_r, Vec* phi, Vec* reaction,
                                                  SpMat* jacobian, SpMat* curvature) const {
  EvaluatePairs("GapsReactionAndDerivatives", u,
                {.r = &r,
                 .curvature_r = &curvature_r,
                 .phi = phi,
                 .reaction = reaction,
                 .jacobian = jacobian,
                 .curvature = curvature});
}

}  // namespace cb
