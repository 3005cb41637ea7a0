#include "solvers/contact_block_factor.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <vector>

#include "solvers/interruptible_cholmod.h"

namespace cb {
namespace {

// The contact-block factorisation is tried from this many dofs on, when the contact dofs are at
// most 1 / kMaxContactFraction of them.
constexpr int kMinDofs = 1000;
constexpr int kMaxContactFraction = 8;

// The lower triangle of A_ii's pattern with its whole diagonal, in compressed columns straight
// from A's lower triangle (count, prefix sum, fill): A's entries come column by column with
// rows increasing from the diagonal (JacobianBlocks::stiffness_lower), and renumbering the
// interior dofs in their order keeps that, so a missing diagonal goes first in its column.
// The values are ones; only the pattern is analysed.
SpMat InteriorPattern(const JacobianBlocks& blocks, const std::vector<int>& interior_index,
                      int ni) {
  std::vector<int> count(ni, 0);
  std::vector<char> has_diagonal(ni, 0);
  for (const JacobianBlocks::Entry& a : blocks.stiffness_lower) {
    const int i = interior_index[a.row];
    const int j = interior_index[a.col];
    if (i < 0 || j < 0) continue;
    ++count[j];
    if (i == j) has_diagonal[j] = 1;
  }
  SpMat aii(ni, ni);
  int* outer = aii.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < ni; ++j) outer[j + 1] = outer[j] + count[j] + (has_diagonal[j] ? 0 : 1);
  aii.resizeNonZeros(outer[ni]);
  std::fill(aii.valuePtr(), aii.valuePtr() + outer[ni], 1.0);
  int* inner = aii.innerIndexPtr();
  std::vector<int> next(outer, outer + ni);
  for (int j = 0; j < ni; ++j) {
    if (!has_diagonal[j]) inner[next[j]++] = j;
  }
  for (const JacobianBlocks::Entry& a : blocks.stiffness_lower) {
    const int i = interior_index[a.row];
    const int j = interior_index[a.col];
    if (i >= 0 && j >= 0) inner[next[j]++] = i;
  }
  return aii;
}

}  // namespace

void ContactBlockFactor::Reset() {
  factor_.reset();
  possible_ = false;
}

void ContactBlockFactor::Analyse(const JacobianBlocks& blocks,
                                 const std::vector<ScatterPattern::Entry>& kc_entries,
                                 const std::vector<int>& kc_slots, SpMat* kc) {
  const int d = blocks.num_dofs;
  num_dofs_ = d;
  contact_dofs_.assign(blocks.pair_dof.begin(), blocks.pair_dof.end());
  std::sort(contact_dofs_.begin(), contact_dofs_.end());
  contact_dofs_.erase(std::unique(contact_dofs_.begin(), contact_dofs_.end()), contact_dofs_.end());
  const int nc_dofs = num_contact_dofs();
  contact_index_.assign(d, -1);
  for (int k = 0; k < nc_dofs; ++k) contact_index_[contact_dofs_[k]] = k;
  possible_ = false;
  interrupted_ = false;
  factor_holds_ = false;
  factored_stiffness_.clear();
  if (nc_dofs == 0 || d < kMinDofs || kMaxContactFraction * nc_dofs > d) return;
  // The slots of Kc's diagonal on the contact dofs (every contact dof has one: the s == t
  // terms of the springs).
  kc_contact_diagonal_slot_.assign(nc_dofs, -1);
  for (std::size_t k = blocks.stiffness_lower.size(); k < kc_entries.size(); ++k) {
    if (kc_entries[k].first == kc_entries[k].second) {
      kc_contact_diagonal_slot_[contact_index_[kc_entries[k].first]] = kc_slots[k];
    }
  }
  permutation_.clear();
  // An analysis an interrupt abandoned is done again by the next Factorize.
  possible_ = AnalyseInOrder(blocks, kc) || interrupted_;
}

// The analysis of Kc in the order permutation_ (found first when there is none); false unless
// CHOLMOD kept that order (the trailing block of L is then L_cc), or on an interrupt.
bool ContactBlockFactor::AnalyseInOrder(const JacobianBlocks& blocks, SpMat* kc) {
  if (permutation_.empty()) {
    permutation_ = InteriorOrdering(blocks);
    if (permutation_.empty()) return false;
    const int nc_dofs = num_contact_dofs();
    for (int k = 0; k < nc_dofs; ++k) permutation_[num_dofs_ - nc_dofs + k] = contact_dofs_[k];
  }
  ++num_analyses_;
  factor_ = AnalyseInterruptibly(cholmod_, kc, permutation_.data(), &interrupted_);
  if (!factor_) return false;
  const int* kept = static_cast<const int*>(factor_->Perm);
  return std::equal(permutation_.begin(), permutation_.end(), kept);
}

// The permutation of the dofs whose first d - c entries order the interior dofs as CHOLMOD's
// default analysis of the pattern of A_ii does (the rest is left for c); empty when that
// analysis fails.
std::vector<int> ContactBlockFactor::InteriorOrdering(const JacobianBlocks& blocks) {
  const int d = blocks.num_dofs;
  const int ni = d - num_contact_dofs();
  std::vector<int> interior;
  std::vector<int> interior_index(d, -1);
  for (int j = 0; j < d; ++j) {
    if (contact_index_[j] < 0) {
      interior_index[j] = static_cast<int>(interior.size());
      interior.push_back(j);
    }
  }
  SpMat aii = InteriorPattern(blocks, interior_index, ni);
  const CholmodFactor interior_symbolic =
      AnalyseInterruptibly(cholmod_, &aii, nullptr, &interrupted_);
  if (!interior_symbolic) return {};
  std::vector<int> permutation(d);
  const int* ip = static_cast<const int*>(interior_symbolic->Perm);
  for (int k = 0; k < ni; ++k) permutation[k] = interior[ip[k]];
  return permutation;
}

bool ContactBlockFactor::Factorize(const JacobianBlocks& blocks, const double* values,
                                   const std::vector<double>& pair_spring,
                                   const std::vector<int>& kc_slots, SpMat* kc) {
  interrupted_ = false;
  // After an interrupt abandoned the factor (the worker took it), it is analysed again.
  if (!factor_ && !AnalyseInOrder(blocks, kc)) {
    possible_ = interrupted_;  // an interrupted analysis is tried again
    return false;
  }
  const double* val = values;
  const std::vector<JacobianBlocks::Entry>& a_entries = blocks.stiffness_lower;
  const std::size_t num_a = a_entries.size();
  bool same = factor_->minor == factor_->n && factored_stiffness_.size() == num_a;
  for (std::size_t k = 0; same && k < num_a; ++k) {
    same = val[a_entries[k].slot] == factored_stiffness_[k];
  }
  const int nc_dofs = num_contact_dofs();
  if (!same) {
    if (!factored_stiffness_.empty()) {
      // A changed: a tangent stiffness. Refactorising the big factor every iteration would
      // cost as much as factorising Kc whole, with a worse ordering: that is done instead.
      possible_ = false;
      return false;
    }
    factored_stiffness_.resize(num_a);
    for (std::size_t k = 0; k < num_a; ++k) factored_stiffness_[k] = val[a_entries[k].slot];
    factor_holds_ = false;
    double* kv = kc->valuePtr();
    std::fill(kv, kv + kc->nonZeros(), 0.0);
    for (std::size_t k = 0; k < num_a; ++k) kv[kc_slots[k]] += val[a_entries[k].slot];
    diagonal_shift_.resize(nc_dofs);
    for (int k = 0; k < nc_dofs; ++k) {
      const int src = blocks.stiffness_diagonal_slot[contact_dofs_[k]];
      const double a = src >= 0 ? std::abs(val[src]) : 0.0;
      diagonal_shift_[k] = a > 0.0 ? a : 1.0;
      kv[kc_contact_diagonal_slot_[k]] += diagonal_shift_[k];
    }
    // The first iteration's big factorisation (P1 n = 300: seconds to tens of seconds), on a
    // worker an interrupt abandons.
    if (!FactorizeInterruptibly(cholmod_, kc, &factor_, &interrupted_)) {
      if (interrupted_) factored_stiffness_.clear();  // factorised again, from the start
      return false;
    }
    if (!factor_->is_super) return false;
    ReadTrailingFactor();
    s_cc_.noalias() =
        trailing_factor_.triangularView<Eigen::Lower>() * trailing_factor_.transpose();
    s_cc_.diagonal() -= diagonal_shift_;
    factor_holds_ = true;
    ++generation_;
  }
  if (!factor_holds_) return false;
  // M = S_cc + G^T W G (lower triangle; the pairs' dofs are increasing, and so are their
  // places among the contact dofs).
  Mat& m = contact_block_.matrix();
  m = s_cc_;
  for (int p = 0; p < blocks.num_pairs; ++p) {
    const double w = pair_spring[p];
    for (int s = blocks.pair_begin[p]; s < blocks.pair_begin[p + 1]; ++s) {
      const double ws = w * val[blocks.g_slot[s]];
      const int cs = contact_index_[blocks.pair_dof[s]];
      for (int t = blocks.pair_begin[p]; t <= s; ++t) {
        m(cs, contact_index_[blocks.pair_dof[t]]) += ws * val[blocks.g_slot[t]];
      }
    }
  }
  const bool factorized = contact_block_.Factorize();
  interrupted_ = contact_block_.interrupted();
  return factorized;
}

void ContactBlockFactor::ReadTrailingFactor() {
  // Columns and rows >= ni, in the order of c.
  const int nc_dofs = num_contact_dofs();
  const int ni = num_dofs_ - nc_dofs;
  trailing_factor_.setZero(nc_dofs, nc_dofs);
  const int* super = static_cast<const int*>(factor_->super);
  const int* pi = static_cast<const int*>(factor_->pi);
  const int* px = static_cast<const int*>(factor_->px);
  const int* rows = static_cast<const int*>(factor_->s);
  const double* lx = static_cast<const double*>(factor_->x);
  for (std::size_t k = 0; k < factor_->nsuper; ++k) {
    const int k1 = super[k], k2 = super[k + 1];
    if (k2 <= ni) continue;
    const int nsrow = pi[k + 1] - pi[k];
    for (int col = std::max(k1, ni); col < k2; ++col) {
      const double* column = lx + px[k] + static_cast<std::ptrdiff_t>(col - k1) * nsrow;
      for (int q = col - k1; q < nsrow; ++q) {
        trailing_factor_(rows[pi[k] + q] - ni, col - ni) = column[q];
      }
    }
  }
}

bool ContactBlockFactor::Forward(const Mat& b, Mat* out) {
  if (!TwoPhases(CHOLMOD_P, CHOLMOD_L, b.data(), static_cast<int>(b.cols()), out)) return false;
  auto tail = out->bottomRows(num_contact_dofs());
  tail = (trailing_factor_.triangularView<Eigen::Lower>() * tail).eval();
  return true;
}

void ContactBlockFactor::ApplyMiddleInverse(Mat* v) const {
  const int nc_dofs = num_contact_dofs();
  const int rows = static_cast<int>(v->rows());
  contact_block_.SolveInPlace(v->data() + (rows - nc_dofs), rows, static_cast<int>(v->cols()));
}

bool ContactBlockFactor::Backward(Mat w, Mat* out) {
  auto tail = w.bottomRows(num_contact_dofs());
  tail = (trailing_factor_.transpose().triangularView<Eigen::Upper>() * tail).eval();
  return TwoPhases(CHOLMOD_Lt, CHOLMOD_Pt, w.data(), static_cast<int>(w.cols()), out);
}

bool ContactBlockFactor::TwoPhases(int first, int second, const double* in, int cols, Mat* out) {
  if (!cholmod_->SolvePhase(first, factor_, in, num_dofs_, cols, &solve_buffer_1_) ||
      !cholmod_->SolvePhase(second, factor_, solve_buffer_1_.data(), num_dofs_, cols,
                            &solve_buffer_2_)) {
    return false;
  }
  out->resize(num_dofs_, cols);
  std::memcpy(out->data(), solve_buffer_2_.data(), sizeof(double) * out->size());
  return true;
}

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
