#include "solvers/interior_elimination.h"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <utility>

#include "solvers/jacobian_blocks.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
#include "core/sparse.h"
#include "solvers/cholmod_wrappers.h"
#include "solvers/contact_block_factor.h"
#endif

namespace cb {

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
struct InteriorElimination::BlockRoute {
  Cholmod cholmod;  // first: it outlives the factor below
  ContactBlockFactor factor{&cholmod};
  SpMat kc;
};
#else
struct InteriorElimination::BlockRoute {};
#endif

InteriorElimination::InteriorElimination() = default;
InteriorElimination::~InteriorElimination() = default;

namespace {

// The contact dofs of `blocks`, increasing, and their place per dof (-1 for the interior).
std::vector<int> ContactDofs(const JacobianBlocks& blocks, std::vector<int>* index) {
  std::vector<int> dofs(blocks.pair_dof.begin(), blocks.pair_dof.end());
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  index->assign(blocks.num_dofs, -1);
  for (std::size_t k = 0; k < dofs.size(); ++k) (*index)[dofs[k]] = static_cast<int>(k);
  return dofs;
}

// A_cc (dense, both triangles) from A's lower triangle at `values`.
Mat ContactStiffness(const JacobianBlocks& blocks, const std::vector<int>& contact_index,
                     int num_contact, const double* values) {
  Mat a_cc = Mat::Zero(num_contact, num_contact);
  for (const JacobianBlocks::Entry& a : blocks.stiffness_lower) {
    const int i = contact_index[a.row], j = contact_index[a.col];
    if (i < 0 || j < 0) continue;
    a_cc(i, j) += values[a.slot];
    if (i != j) a_cc(j, i) += values[a.slot];
  }
  return a_cc;
}

}  // namespace

bool InteriorElimination::Factorize(const SpMat& jacobian, int num_dofs, int num_pairs) {
  uses_contact_block_ = false;
  interrupted_ = false;
  if (FactorizeByBlock(jacobian, num_dofs, num_pairs)) {
    uses_contact_block_ = true;
    return true;
  }
  if (interrupted_) return false;
  return FactorizeSimplicial(jacobian, num_dofs, num_pairs);
}

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
bool InteriorElimination::FactorizeByBlock(const SpMat& jacobian, int num_dofs, int num_pairs) {
  std::optional<JacobianBlocks> blocks = FindJacobianBlocks(jacobian, num_dofs, num_pairs);
  if (!blocks) return false;
  std::vector<int> contact_index;
  contact_dofs_ = ContactDofs(*blocks, &contact_index);
  // Kc's pattern as ContactBlockFactor reads it: A's lower triangle, then a diagonal entry per
  // contact dof (the springs, here all zero: A + D0 alone is wanted).
  std::vector<ScatterPattern::Entry> entries;
  entries.reserve(blocks->stiffness_lower.size() + contact_dofs_.size());
  for (const JacobianBlocks::Entry& a : blocks->stiffness_lower) entries.emplace_back(a.row, a.col);
  for (int dof : contact_dofs_) entries.emplace_back(dof, dof);
  const ScatterPattern kc(num_dofs, num_dofs, entries);
  block_ = std::make_unique<BlockRoute>();
  block_->kc = kc.pattern();
  block_->factor.Analyse(*blocks, entries, kc.slots(), &block_->kc);
  interrupted_ = block_->factor.interrupted();
  if (interrupted_ || !block_->factor.possible()) return false;
  const std::vector<double> no_springs(num_pairs, 0.0);
  // M = S_cc alone may be singular (a body held by its contacts only); S_cc is what is read.
  block_->factor.Factorize(*blocks, jacobian.valuePtr(), no_springs, kc.slots(), &block_->kc);
  interrupted_ = block_->factor.interrupted();
  const Mat* s_cc = block_->factor.stiffness_schur_complement();
  if (s_cc == nullptr || block_->factor.contact_dofs() != contact_dofs_) return false;
  const int c = static_cast<int>(contact_dofs_.size());
  correction_ = *s_cc - ContactStiffness(*blocks, contact_index, c, jacobian.valuePtr());
  return correction_.allFinite();
}
#else
bool InteriorElimination::FactorizeByBlock(const SpMat& /*jacobian*/, int /*num_dofs*/,
                                           int /*num_pairs*/) {
  return false;
}
#endif

bool InteriorElimination::FactorizeSimplicial(const SpMat& jacobian, int num_dofs, int num_pairs) {
  block_.reset();
  std::optional<JacobianBlocks> blocks = FindJacobianBlocks(jacobian, num_dofs, num_pairs);
  if (!blocks) return false;
  std::vector<int> contact_index;
  contact_dofs_ = ContactDofs(*blocks, &contact_index);
  interior_dofs_.clear();
  std::vector<int> interior_index(num_dofs, -1);
  for (int j = 0; j < num_dofs; ++j) {
    if (contact_index[j] >= 0) continue;
    interior_index[j] = static_cast<int>(interior_dofs_.size());
    interior_dofs_.push_back(j);
  }
  const int ni = static_cast<int>(interior_dofs_.size());
  const int c = static_cast<int>(contact_dofs_.size());
  const double* values = jacobian.valuePtr();
  std::vector<Triplet> t;
  a_ic_.setZero(ni, c);
  for (const JacobianBlocks::Entry& a : blocks->stiffness_lower) {
    const int ii = interior_index[a.row], ij = interior_index[a.col];
    if (ii >= 0 && ij >= 0) {
      t.emplace_back(ii, ij, values[a.slot]);  // lower triangle, as the factor reads it
    } else if (ii >= 0) {
      a_ic_(ii, contact_index[a.col]) += values[a.slot];
    } else if (ij >= 0) {
      a_ic_(ij, contact_index[a.row]) += values[a.slot];
    }
  }
  SpMat a_ii(ni, ni);
  a_ii.setFromTriplets(t.begin(), t.end());
  interior_factor_.compute(a_ii);
  if (interior_factor_.info() != Eigen::Success || (interior_factor_.vectorD().array() <= 0).any())
    return false;
  const Mat solved = interior_factor_.solve(a_ic_);
  correction_ = -(a_ic_.transpose() * solved);
  correction_ = 0.5 * (correction_ + correction_.transpose()).eval();  // symmetric to rounding
  return correction_.allFinite();
}

bool InteriorElimination::Condense(const Vec& b, Vec* b_tilde) {
  const int c = static_cast<int>(contact_dofs_.size());
  b_tilde->resize(c);
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  if (uses_contact_block_) {
    if (!block_->factor.Forward(b, &forward_b_)) return false;
    *b_tilde = forward_b_.bottomRows(c).col(0);
    return b_tilde->allFinite();
  }
#endif
  const int ni = static_cast<int>(interior_dofs_.size());
  Vec b_i(ni);
  for (int k = 0; k < ni; ++k) b_i[k] = b[interior_dofs_[k]];
  solved_b_i_ = interior_factor_.solve(b_i);
  for (int k = 0; k < c; ++k) (*b_tilde)[k] = b[contact_dofs_[k]];
  b_tilde->noalias() -= a_ic_.transpose() * solved_b_i_;
  return b_tilde->allFinite();
}

bool InteriorElimination::Recover(const Vec& du_c, Vec* du) {
  const int c = static_cast<int>(contact_dofs_.size());
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  if (uses_contact_block_) {
    Mat w = forward_b_;
    const Eigen::Index ni = w.rows() - c;
    w.topRows(ni) *= -1.0;
    w.bottomRows(c).col(0) = du_c;
    Mat out;
    if (!block_->factor.Backward(std::move(w), &out)) return false;
    *du = out.col(0);
    return du->allFinite();
  }
#endif
  const int ni = static_cast<int>(interior_dofs_.size());
  const Vec du_i = -(solved_b_i_ + interior_factor_.solve(a_ic_ * du_c));
  du->resize(ni + c);
  for (int k = 0; k < ni; ++k) (*du)[interior_dofs_[k]] = du_i[k];
  for (int k = 0; k < c; ++k) (*du)[contact_dofs_[k]] = du_c[k];
  return du->allFinite();
}

}  // namespace cb
