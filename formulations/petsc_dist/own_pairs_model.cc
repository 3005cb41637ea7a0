#include "formulations/petsc_dist/own_pairs_model.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace cb {

namespace {

std::vector<ContactPair> PairsAt(const std::vector<ContactPair>& pairs,
                                 const std::vector<int>& own) {
  std::vector<ContactPair> selected;
  selected.reserve(own.size());
  for (std::size_t q = 0; q < own.size(); ++q) {
    const int p = own[q];
    if (p < 0 || p >= static_cast<int>(pairs.size()) || (q > 0 && p <= own[q - 1])) {
      throw std::invalid_argument("own: pair " + std::to_string(p) +
                                  " is not one of the model's pairs in ascending order");
    }
    selected.push_back(pairs[static_cast<std::size_t>(p)]);
  }
  return selected;
}

// The load on the displacement rows among [first_row, last_row), zero elsewhere.
Vec LoadOnRows(const Vec& load, int first_row, int last_row) {
  Vec own = Vec::Zero(load.size());
  const int first = std::clamp(first_row, 0, static_cast<int>(load.size()));
  const int last = std::clamp(last_row, first, static_cast<int>(load.size()));
  own.segment(first, last - first) = load.segment(first, last - first);
  return own;
}

}  // namespace

OwnPairsModel::OwnPairsModel(const BodyContactModel& model, std::vector<int> own, int first_row,
                             int last_row)
    : own_model_(std::make_shared<BodyContactModel>(
          model.body().Restricted({}), model.obstacles(), PairsAt(model.pairs(), own),
          LoadOnRows(model.load_pattern(), first_row, last_row))),
      own_(std::move(own)),
      num_pairs_(model.num_pairs()),
      linear_(model.is_linear()) {}

void OwnPairsModel::Select(const Vec& all, Vec* to) const {
  if (all.size() != num_pairs_) {
    throw std::invalid_argument("OwnPairsModel: r has size " + std::to_string(all.size()) +
                                ", expected " + std::to_string(num_pairs_));
  }
  to->resize(static_cast<Eigen::Index>(own_.size()));
  for (std::size_t q = 0; q < own_.size(); ++q) (*to)[q] = all[own_[q]];
}

void OwnPairsModel::Spread(const Vec& own, Vec* all) const {
  all->setZero(num_pairs_);
  for (std::size_t q = 0; q < own_.size(); ++q) (*all)[own_[q]] = own[q];
}

// Row q of `own` is pair own_[q]: the column-compressed storage keeps its order (own_ ascends),
// so only the row indices change. `all` keeps its storage once shaped.
void OwnPairsModel::Renumber(const SpMat& own, SpMat* all) const {
  if (all->rows() != num_pairs_ || all->cols() != own.cols() || all->nonZeros() != own.nonZeros() ||
      !all->isCompressed()) {
    *all = own;
    all->conservativeResize(num_pairs_, own.cols());
    all->makeCompressed();
  }
  std::copy_n(own.outerIndexPtr(), own.outerSize() + 1, all->outerIndexPtr());
  std::copy_n(own.valuePtr(), own.nonZeros(), all->valuePtr());
  const int* rows = own.innerIndexPtr();
  int* renumbered = all->innerIndexPtr();
  for (Eigen::Index k = 0; k < own.nonZeros(); ++k) renumbered[k] = own_[rows[k]];
}

void OwnPairsModel::Gaps(const Vec& u, Vec* phi) const {
  own_model_->Gaps(u, &phi_);
  Spread(phi_, phi);
}

void OwnPairsModel::GapJacobian(const Vec& u, SpMat* jacobian) const {
  own_model_->GapJacobian(u, &jacobian_);
  Renumber(jacobian_, jacobian);
}

void OwnPairsModel::GeneralisedReaction(const Vec& u, const Vec& r, Vec* reaction) const {
  Select(r, &r_);
  own_model_->GeneralisedReaction(u, r_, reaction);
}

void OwnPairsModel::GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const {
  Select(r, &curvature_r_);
  own_model_->GapCurvature(u, curvature_r_, curvature);
}

void OwnPairsModel::GapsAndReaction(const Vec& u, const Vec& r, Vec* phi, Vec* reaction) const {
  Select(r, &r_);
  own_model_->GapsAndReaction(u, r_, &phi_, reaction);
  Spread(phi_, phi);
}

void OwnPairsModel::GapDerivatives(const Vec& u, const Vec& r, SpMat* jacobian,
                                   SpMat* curvature) const {
  Select(r, &curvature_r_);
  own_model_->GapDerivatives(u, curvature_r_, &jacobian_, curvature);
  Renumber(jacobian_, jacobian);
}

void OwnPairsModel::GapsReactionAndDerivatives(const Vec& u, const Vec& r, const Vec& curvature_r,
                                               Vec* phi, Vec* reaction, SpMat* jacobian,
                                               SpMat* curvature) const {
  Select(r, &r_);
  Select(curvature_r, &curvature_r_);
  own_model_->GapsReactionAndDerivatives(u, r_, curvature_r_, &phi_, reaction, &jacobian_,
                                         curvature);
  Spread(phi_, phi);
  Renumber(jacobian_, jacobian);
}

}  // namespace cb
