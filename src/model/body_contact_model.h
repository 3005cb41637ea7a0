// The contact model of an elastic body against rigid obstacles: gaps come from the obstacles'
// signed distances evaluated at the contact nodes' current positions.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/sparse.h"
#include "model/contact_model.h"
#include "model/elastic_body.h"
#include "model/obstacle.h"

namespace cb {

// A contact candidate: one node of the body against one obstacle.
struct ContactPair {
  int node = 0;
  int obstacle = 0;
};

class BodyContactModel final : public ContactModel {
 public:
  // Throws std::invalid_argument on a pair naming an unknown node or obstacle, an obstacle of
  // another dimension, or a load of the wrong size.
  BodyContactModel(std::shared_ptr<const ElasticBody> body,
                   std::vector<std::shared_ptr<const Obstacle>> obstacles,
                   std::vector<ContactPair> pairs, Vec load_pattern);

  int num_dofs() const override { return body_->num_dofs(); }
  int num_pairs() const override { return static_cast<int>(pairs_.size()); }
  bool is_linear() const override;
  bool has_constant_stiffness() const override;
  double Energy(const Vec& u) const override { return body_->Energy(u); }
  void InternalForce(const Vec& u, Vec* force) const override { body_->InternalForce(u, force); }
  void Stiffness(const Vec& u, SpMat* stiffness) const override { body_->Stiffness(u, stiffness); }
  void InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const override {
    body_->InternalForceMagnitudes(u, magnitudes);
  }
  std::vector<std::pair<int, int>> StiffnessEntries() const override {
    return body_->StiffnessEntries();
  }
  void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const override {
    body_->AddStiffness(u, scale, slots, values);
  }
  void Gaps(const Vec& u, Vec* phi) const override;
  void GapJacobian(const Vec& u, SpMat* jacobian) const override;
  void GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const override;
  void GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const override;
  void GapsAndReaction(const Vec& u, const Vec& r, Vec* phi, Vec* reaction) const override;
  void GapDerivatives(const Vec& u, const Vec& r, SpMat* jacobian, SpMat* curvature) const override;
  void InternalForceAndStiffness(const Vec& u, Vec* force, double scale, const int* slots,
                                 double* values) const override {
    body_->InternalForceAndStiffness(u, force, scale, slots, values);
  }
  void GapsReactionAndDerivatives(const Vec& u, const Vec& r, const Vec& curvature_r, Vec* phi,
                                  Vec* reaction, SpMat* jacobian, SpMat* curvature) const override;
  const Vec& load_pattern() const override { return load_; }

  const ElasticBody& body() const { return *body_; }
  const std::vector<std::shared_ptr<const Obstacle>>& obstacles() const { return obstacles_; }
  const std::vector<ContactPair>& pairs() const { return pairs_; }

 private:
  std::shared_ptr<const ElasticBody> body_;
  std::vector<std::shared_ptr<const Obstacle>> obstacles_;
  std::vector<ContactPair> pairs_;
  // varphi of pair p at its node's current position, up to `order`.
  void EvaluatePair(int p, const Vec& u, Obstacle::Order order, ObstacleLocal* local) const;
  // What a pass over the pairs fills (null: skipped) and the reaction weights it reads: r for
  // the reaction grad phi^T r, curvature_r for sum_p r_p hess phi_p.
  struct PairOutputs {
    const Vec* r = nullptr;
    const Vec* curvature_r = nullptr;
    Vec* phi = nullptr;
    Vec* reaction = nullptr;
    SpMat* jacobian = nullptr;
    SpMat* curvature = nullptr;
  };
  // The pair loop behind the public functions; `what` names the public function in size errors.
  void EvaluatePairs(const char* what, const Vec& u, const PairOutputs& out) const;

  Vec load_;
  std::vector<Point> pair_reference_;          // X of each pair's node
  std::vector<std::array<int, 3>> pair_dofs_;  // its dofs, -1 where supported
  // Whether row p of grad phi has an entry on the pair's component c: a free component, and for
  // a flat obstacle one its constant normal does not vanish on (a wall's pairs act on one dof).
  std::vector<std::array<bool, 3>> pair_gradient_entry_;
  std::vector<int> curved_pairs_;     // pairs on curved obstacles, in order
  ScatterPattern jacobian_pattern_;   // row p on pair p's gradient entries
  ScatterPattern curvature_pattern_;  // node blocks of pairs on curved obstacles
};

}  // namespace cb
