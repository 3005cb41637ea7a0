#include "solvers/condensed_system.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <utility>

#include "solvers/interruptible_cholmod.h"

namespace cb {
namespace {

// A pair's spring w may add at most this multiple of the largest stiffness diagonal on its
// dofs: about 1/sqrt(eps), which balances the rounding of the spring (eps * cap relative to
// the stiffness) against the model error of the cap (1 / cap), so refinement contracts by
// ~1e-8 per sweep.
constexpr double kPenaltyCap = 1e8;

bool SamePattern(const SpMat& a, const SpMat& b) {
  return a.rows() == b.rows() && a.nonZeros() == b.nonZeros() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

}  // namespace

void CondensedSystem::Analyse(JacobianBlocks blocks) {
  blocks_ = std::move(blocks);
  const int d = blocks_.num_dofs, nc = blocks_.num_pairs;
  // Kc = A (lower) + the pair springs G_p^T w_p G_p (lower).
  std::size_t num_entries = blocks_.stiffness_lower.size();
  for (int p = 0; p < nc; ++p) {
    const std::size_t k = blocks_.pair_begin[p + 1] - blocks_.pair_begin[p];
    num_entries += k * (k + 1) / 2;
  }
  std::vector<ScatterPattern::Entry> kc_entries;
  kc_entries.reserve(num_entries);  // filled once, without regrowing
  for (const JacobianBlocks::Entry& a : blocks_.stiffness_lower)
    kc_entries.emplace_back(a.row, a.col);
  for (int p = 0; p < nc; ++p) {
    for (int s = blocks_.pair_begin[p]; s < blocks_.pair_begin[p + 1]; ++s) {
      for (int t = blocks_.pair_begin[p]; t <= s; ++t) {
        kc_entries.emplace_back(blocks_.pair_dof[s], blocks_.pair_dof[t]);
      }
    }
  }
  const ScatterPattern kc(d, d, kc_entries);
  // kc_ keeps the pattern it was given (only its values change): the pattern of the analyses.
  const bool same_kc = kc_.rows() == d && SamePattern(kc.pattern(), kc_);
  kc.Reset(&kc_);  // copied (onto huge pages) only when the pattern is new
  kc_slots_ = kc.slots();
  if (!same_kc) {
    // The factorisations belong to the old pattern: analysed again.
    whole_factor_.reset();
    contact_block_.Reset();
    contact_block_active_ = false;
    contact_block_.Analyse(blocks_, kc_entries, kc_slots_, &kc_);
  }
  pair_spring_.resize(nc);
  da_over_e_.resize(nc);
  e_.resize(nc);
  db_capped_.resize(nc);
}

bool CondensedSystem::Factorize(const double* values, double coupling) {
  contact_block_active_ = false;
  interrupted_ = false;
  if (!CondensePairs(values, coupling)) return false;
  contact_block_active_ = contact_block_.possible() &&
                          contact_block_.Factorize(blocks_, values, pair_spring_, kc_slots_, &kc_);
  if (!contact_block_active_ && contact_block_.possible() && contact_block_.interrupted()) {
    interrupted_ = true;  // abandoned: no other factorisation to start
    return false;
  }
  if (!contact_block_active_ && !FactorizeWhole(values)) return false;  // not positive definite
  return FactorizeBorder(values);
}

bool CondensedSystem::CondensePairs(const double* values, double coupling) {
  const double* val = values;
  double max_diag = 0.0;
  for (int i = 0; i < blocks_.num_dofs; ++i) {
    const int diag = blocks_.stiffness_diagonal_slot[i];
    if (diag >= 0) max_diag = std::max(max_diag, std::abs(val[diag]));
  }
  if (!(max_diag > 0.0)) max_diag = 1.0;
  capped_pairs_ = 0;
  for (int p = 0; p < blocks_.num_pairs; ++p) {
    const double e = val[blocks_.e_slot[p]];
    const double da = blocks_.da_slot[p] >= 0 ? val[blocks_.da_slot[p]] : 0.0;
    const double db = blocks_.db_slot[p] >= 0 ? val[blocks_.db_slot[p]] : 0.0;
    if (e == 0.0 || (da == 0.0 && db == 0.0)) return false;
    // H = -coupling G^T: checked, since the condensed matrix assumes it.
    double stiffness = 0.0, g2 = 0.0;
    for (int s = blocks_.pair_begin[p]; s < blocks_.pair_begin[p + 1]; ++s) {
      const double g = val[blocks_.g_slot[s]];
      const double h = val[blocks_.h_slot[s]];
      if (!(std::abs(h + coupling * g) <= 1e-10 * std::abs(h))) return false;
      g2 = std::max(g2, g * g);
      const int diag = blocks_.stiffness_diagonal_slot[blocks_.pair_dof[s]];
      if (diag >= 0) stiffness = std::max(stiffness, std::abs(val[diag]));
    }
    if (!(stiffness > 0.0)) stiffness = max_diag;
    const double cap = g2 > 0.0 ? kPenaltyCap * stiffness / g2 : 0.0;
    double w = db != 0.0 ? -coupling * da / (e * db) : std::numeric_limits<double>::infinity();
    double bt = db;
    if (g2 > 0.0 && std::abs(w) > cap) {
      if (w < 0.0 || da == 0.0) return false;  // a huge negative spring: not for Cholesky
      w = cap;
      bt = -coupling * da / (e * w);
      ++capped_pairs_;
    } else if (db == 0.0) {
      return false;  // a pair on no dof with Db = 0: r is undetermined here
    }
    pair_spring_[p] = w;
    e_[p] = e;
    da_over_e_[p] = da / e;
    db_capped_[p] = bt;
  }
  return true;
}

bool CondensedSystem::FactorizeWhole(const double* values) {
  const double* val = values;
  double* kv = kc_.valuePtr();
  std::fill(kv, kv + kc_.nonZeros(), 0.0);
  std::size_t k = 0;
  for (; k < blocks_.stiffness_lower.size(); ++k) {
    kv[kc_slots_[k]] += val[blocks_.stiffness_lower[k].slot];
  }
  for (int p = 0; p < blocks_.num_pairs; ++p) {
    const double w = pair_spring_[p];
    for (int s = blocks_.pair_begin[p]; s < blocks_.pair_begin[p + 1]; ++s) {
      const double ws = w * val[blocks_.g_slot[s]];
      for (int t = blocks_.pair_begin[p]; t <= s; ++t) {
        kv[kc_slots_[k++]] += ws * val[blocks_.g_slot[t]];
      }
    }
  }
  if (!whole_factor_) {
    // (Again after an interrupt abandoned the factor: interruptible_cholmod.h.)
    ++num_analyses_;
    whole_factor_ = AnalyseInterruptibly(&cholmod_, &kc_, nullptr, &interrupted_);
    if (!whole_factor_) return false;
  }
  return FactorizeInterruptibly(&cholmod_, &kc_, &whole_factor_, &interrupted_);
}

bool CondensedSystem::FactorizeBorder(const double* values) {
  const double* val = values;
  const int d = blocks_.num_dofs, nc = blocks_.num_pairs, m = blocks_.num_border;
  // B = U1 - H Db~^-1 U3, C = V^T - G^T (E^-1 Vg^T) + G^T (Da E^-1 Db~^-1 Vr^T),
  // Wc = W - Vr Db~^-1 U3, then S = Wc - C^T Kc^-1 B.
  u3_.setZero(nc, m);
  vg_transposed_.setZero(nc, m);
  vr_transposed_.setZero(nc, m);
  for (const auto& t : blocks_.u3) u3_(t.row, t.col) += val[t.slot];
  for (const auto& t : blocks_.vg) vg_transposed_(t.col, t.row) += val[t.slot];
  for (const auto& t : blocks_.vr) vr_transposed_(t.col, t.row) += val[t.slot];
  border_b_.setZero(d, m);
  border_c_.setZero(d, m);
  Mat wc = Mat::Zero(m, m);
  for (const auto& t : blocks_.u1) border_b_(t.row, t.col) += val[t.slot];
  for (const auto& t : blocks_.v) border_c_(t.col, t.row) += val[t.slot];
  for (const auto& t : blocks_.w) wc(t.row, t.col) += val[t.slot];
  for (int p = 0; p < nc; ++p) {
    for (int l = 0; l < m; ++l) {
      const double q = u3_(p, l) / db_capped_[p];
      if (q != 0.0) {
        for (int s = blocks_.pair_begin[p]; s < blocks_.pair_begin[p + 1]; ++s) {
          border_b_(blocks_.pair_dof[s], l) -= val[blocks_.h_slot[s]] * q;
        }
        for (int kk = 0; kk < m; ++kk) wc(kk, l) -= vr_transposed_(p, kk) * q;
      }
      const double c =
          -vg_transposed_(p, l) / e_[p] + vr_transposed_(p, l) * da_over_e_[p] / db_capped_[p];
      if (c != 0.0) {
        for (int s = blocks_.pair_begin[p]; s < blocks_.pair_begin[p + 1]; ++s) {
          border_c_(blocks_.pair_dof[s], l) += c * val[blocks_.g_slot[s]];
        }
      }
    }
  }
  if (m > 0 && contact_block_active_) {
    // Kc = Lt Dt Lt^T: then C^T Kc^-1 B = (Lt^-1 C)^T Dt^-1 (Lt^-1 B), forward halves only.
    // The forward solve of U1 (the load column) is kept while the big factor is; the parts on
    // the contact dofs need none (Lt^-1 [0; v_c] = [0; v_c]).
    Mat u1 = Mat::Zero(d, m), v = Mat::Zero(d, m);
    for (const auto& t : blocks_.u1) u1(t.row, t.col) += val[t.slot];
    for (const auto& t : blocks_.v) v(t.col, t.row) += val[t.slot];
    const int generation = contact_block_.generation();
    if (!(forward_u1_generation_ == generation && u1 == forward_u1_of_)) {
      forward_u1_of_ = u1;
      if (!contact_block_.Forward(u1, &forward_u1_)) return false;
      forward_u1_generation_ = generation;
    }
    forward_b_ = forward_u1_;
    if (v.isZero(0.0)) {
      forward_c_.setZero(d, m);
    } else if (!contact_block_.Forward(v, &forward_c_)) {
      return false;
    }
    const std::vector<int>& contact_dofs = contact_block_.contact_dofs();
    const int ni = d - static_cast<int>(contact_dofs.size());
    for (std::size_t k = 0; k < contact_dofs.size(); ++k) {
      const int dof = contact_dofs[k];
      forward_b_.row(ni + k) += border_b_.row(dof) - u1.row(dof);
      forward_c_.row(ni + k) += border_c_.row(dof) - v.row(dof);
    }
    scaled_forward_b_ = forward_b_;
    contact_block_.ApplyMiddleInverse(&scaled_forward_b_);
    const Mat schur = wc - forward_c_.transpose() * scaled_forward_b_;
    if (!schur.allFinite()) return false;
    border_schur_lu_.compute(schur);
    if (border_schur_lu_.rank() < m) return false;
  } else if (m > 0) {
    if (!SolveWhole(border_b_, &kc_inverse_b_)) return false;
    const Mat schur = wc - border_c_.transpose() * kc_inverse_b_;
    if (!schur.allFinite()) return false;
    border_schur_lu_.compute(schur);
    if (border_schur_lu_.rank() < m) return false;
  }
  return true;
}

bool CondensedSystem::SolveWhole(const double* b, int cols, double* x) {
  const int d = blocks_.num_dofs;
  if (!cholmod_.SolvePhase(CHOLMOD_A, whole_factor_, b, d, cols, &whole_solve_buffer_)) {
    return false;
  }
  std::memcpy(x, whole_solve_buffer_.data(), sizeof(double) * static_cast<std::size_t>(d) * cols);
  return true;
}

bool CondensedSystem::SolveWhole(const Mat& b, Mat* x) {
  x->resize(b.rows(), b.cols());
  return SolveWhole(b.data(), static_cast<int>(b.cols()), x->data());
}

bool CondensedSystem::SolveWhole(const Vec& b, Vec* x) {
  x->resize(b.size());
  return SolveWhole(b.data(), 1, x->data());
}

Vec CondensedSystem::BorderRightHandSide(const Vec& b) const {
  const int d = blocks_.num_dofs, nc = blocks_.num_pairs, m = blocks_.num_border;
  const int r2 = d;
  Vec h4 = b.tail(m);
  for (int p = 0; p < nc; ++p) {
    const double b2e = b[r2 + p] / e_[p];
    for (int k = 0; k < m; ++k) {
      h4[k] -= vg_transposed_(p, k) * b2e + vr_transposed_(p, k) * pair_t_[p];
    }
  }
  return h4;
}

bool CondensedSystem::Solve(const double* values, const Vec& b, Vec* x) {
  const double* val = values;
  const int d = blocks_.num_dofs, nc = blocks_.num_pairs, m = blocks_.num_border;
  const int r2 = d, r3 = d + nc, r4 = d + 2 * nc;
  pair_t_.resize(nc);
  h1_ = b.head(d);
  for (int p = 0; p < nc; ++p) {
    const double t = (b[r3 + p] - da_over_e_[p] * b[r2 + p]) / db_capped_[p];
    pair_t_[p] = t;
    if (t != 0.0) {
      for (int s = blocks_.pair_begin[p]; s < blocks_.pair_begin[p + 1]; ++s) {
        h1_[blocks_.pair_dof[s]] -= val[blocks_.h_slot[s]] * t;
      }
    }
  }
  x->resize(b.size());
  if (contact_block_active_) {
    // f = Lt^-1 h1, y from the Schur complement, v = Kc^-1 (h1 - B y) = Lt^-T Dt^-1 (f - Fb y):
    // one forward and one backward solve.
    if (!contact_block_.Forward(h1_, &forward_h_)) return false;
    contact_block_.ApplyMiddleInverse(&forward_h_);
    if (m > 0) {
      Vec h4 = BorderRightHandSide(b);
      h4.noalias() -= forward_c_.transpose() * forward_h_.col(0);
      const Vec y = border_schur_lu_.solve(h4);
      forward_h_.col(0).noalias() -= scaled_forward_b_ * y;
      x->tail(m) = y;
    }
    if (!contact_block_.Backward(forward_h_, &backward_h_)) return false;
    v_ = backward_h_.col(0);
  } else if (!SolveWhole(h1_, &v_)) {
    return false;
  }
  if (m > 0 && !contact_block_active_) {
    Vec h4 = BorderRightHandSide(b);
    h4.noalias() -= border_c_.transpose() * v_;
    const Vec y = border_schur_lu_.solve(h4);
    v_.noalias() -= kc_inverse_b_ * y;
    x->tail(m) = y;
  }
  x->head(d) = v_;
  for (int p = 0; p < nc; ++p) {
    double gv = 0.0;
    for (int s = blocks_.pair_begin[p]; s < blocks_.pair_begin[p + 1]; ++s) {
      gv += val[blocks_.g_slot[s]] * v_[blocks_.pair_dof[s]];
    }
    const double g = (b[r2 + p] - gv) / e_[p];
    double rhs = b[r3 + p] - e_[p] * da_over_e_[p] * g;
    for (int l = 0; l < m; ++l) rhs -= u3_(p, l) * (*x)[r4 + l];
    (*x)[r2 + p] = g;
    (*x)[r3 + p] = rhs / db_capped_[p];
  }
  return true;
}

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
