// The contact-only model of one process of a distributed step system (petsc_dist_adapter.h): the
// body without elements, every obstacle and every pair of the whole model in the whole model's
// numbering, but only this process's pairs (element_partition.h) evaluated, and the load only on
// the rows this process owns. Evaluated by the formulation's own serial step equations, it gives
//   - on this process's pairs' rows, (30) and the complementarity rows exactly as the whole
//     model would (each pair's gap, its gradient and curvature are the pair's alone), and
//   - on the displacement rows, -lambda f / R on this process's rows plus its pairs' share of
//     the contact term -grad phi^T r^ of (29) / R, which sums over the processes to the whole;
// a pair of another process reads phi = 0 with no gradient, and its rows are not this process's
// to keep. The per-pair geometry (the obstacles' distances, normals and curvatures), the work
// of the contact rows, is thus divided among the processes; the rows that read the iterate
// alone ((31) and its variants, (32), (33)) cost every process O(nc + d) arithmetic.
// Written without PETSc, so that the tests check it in every build.
#pragma once

#include <memory>
#include <vector>

#include "model/body_contact_model.h"

namespace cb {

class OwnPairsModel final : public ContactModel {
 public:
  // `model`'s body without elements, its obstacles, its pairs `own` (indices, ascending) and
  // its load on the rows [first_row, last_row) only (rows of the distributed system: those
  // beyond the displacements are ignored). Throws std::invalid_argument on an index outside the
  // model's pairs or not ascending.
  OwnPairsModel(const BodyContactModel& model, std::vector<int> own, int first_row, int last_row);

  int num_dofs() const override { return own_model_->num_dofs(); }
  int num_pairs() const override { return num_pairs_; }
  bool is_linear() const override { return linear_; }
  double Energy(const Vec& u) const override { return own_model_->Energy(u); }
  void InternalForce(const Vec& u, Vec* force) const override {
    own_model_->InternalForce(u, force);
  }
  void Stiffness(const Vec& u, SpMat* stiffness) const override {
    own_model_->Stiffness(u, stiffness);
  }
  std::vector<std::pair<int, int>> StiffnessEntries() const override {
    return own_model_->StiffnessEntries();
  }
  void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const override {
    own_model_->AddStiffness(u, scale, slots, values);
  }
  void InternalForceAndStiffness(const Vec& u, Vec* force, double scale, const int* slots,
                                 double* values) const override {
    own_model_->InternalForceAndStiffness(u, force, scale, slots, values);
  }
  void Gaps(const Vec& u, Vec* phi) const override;
  void GapJacobian(const Vec& u, SpMat* jacobian) const override;
  void GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const override;
  void GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const override;
  void GapsAndReaction(const Vec& u, const Vec& r, Vec* phi, Vec* reaction) const override;
  void GapDerivatives(const Vec& u, const Vec& r, SpMat* jacobian, SpMat* curvature) const override;
  void GapsReactionAndDerivatives(const Vec& u, const Vec& r, const Vec& curvature_r, Vec* phi,
                                  Vec* reaction, SpMat* jacobian, SpMat* curvature) const override;
  const Vec& load_pattern() const override { return own_model_->load_pattern(); }

  // This process's pairs, ascending.
  const std::vector<int>& own_pairs() const { return own_; }

 private:
  // The own pairs' entries of a vector over all pairs, into `to`.
  void Select(const Vec& all, Vec* to) const;
  // The own pairs' values into a vector over all pairs (zero elsewhere).
  void Spread(const Vec& own, Vec* all) const;
  // The own pairs' gap Jacobian (rows in own order) as rows of the whole model's.
  void Renumber(const SpMat& own, SpMat* all) const;

  std::shared_ptr<const BodyContactModel> own_model_;
  std::vector<int> own_;
  int num_pairs_ = 0;
  bool linear_ = false;
  // Work storage reused across evaluations (one model serves one process's evaluations).
  mutable Vec r_, curvature_r_, phi_;
  mutable SpMat jacobian_;
};

}  // namespace cb
