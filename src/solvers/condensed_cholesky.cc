#include "solvers/condensed_cholesky.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <cholmod.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/finite.h"
#include "core/sparse.h"

namespace cb {
namespace {

// A pair's spring w may add at most this multiple of the largest stiffness diagonal on its
// dofs: about 1/sqrt(eps), which balances the rounding of the spring (eps * cap relative to
// the stiffness) against the model error of the cap (1 / cap), so refinement contracts by
// ~1e-8 per sweep.
constexpr double kPenaltyCap = 1e8;
constexpr int kMaxRefinements = 8;
// Systems with fewer dofs d go to the fallback LU.
constexpr int kMinCondensedSize = 1000;
// The contact-block factorisation (SchurFactorize) is tried from this size on, when the contact
// dofs are at most 1 / kSchurMaxFraction of the dofs.
constexpr int kSchurMinSize = 1000;
constexpr int kSchurMaxFraction = 8;
// Refinement stops below this normwise backward error (a few ulps) ...
constexpr double kTargetBackwardError = 8.0 * std::numeric_limits<double>::epsilon();
// ... and the answer is accepted at or below this one; otherwise the LU solves the system.
constexpr double kAcceptBackwardError = 1e-12;

class CondensedCholeskySolver final : public LinearSolver {
 public:
  explicit CondensedCholeskySolver(std::unique_ptr<LinearSolver> fallback)
      : fallback_(std::move(fallback)) {
    cholmod_start(&common_);
    common_.print = 0;
    common_.error_handler = nullptr;
  }
  ~CondensedCholeskySolver() override {
    FreeFactor();
    cholmod_free_dense(&x1_, &common_);
    cholmod_free_dense(&x2_, &common_);
    cholmod_free_dense(&y_, &common_);
    cholmod_free_dense(&e_work_, &common_);
    cholmod_finish(&common_);
  }
  CondensedCholeskySolver(const CondensedCholeskySolver&) = delete;
  CondensedCholeskySolver& operator=(const CondensedCholeskySolver&) = delete;

  std::string name() const override { return "cholmod"; }

  void SetStructure(const JacobianStructure* s) override {
    if (s == nullptr) {
      has_structure_ = false;
      return;
    }
    if (!has_structure_ || s->d != structure_.d || s->nc != structure_.nc ||
        s->coupling != structure_.coupling) {
      analysed_ = false;
    }
    structure_ = *s;
    has_structure_ = true;
  }

  bool Factorize(const SpMat& a) override {
    if (a.rows() != a.cols()) {
      throw std::invalid_argument("cholmod: Factorize needs a square matrix, got " +
                                  std::to_string(a.rows()) + " x " + std::to_string(a.cols()));
    }
    factorized_ = false;
    use_fallback_ = false;
    // Small systems go to the LU: there its refactorisation beats the condensation's fixed
    // costs (P3, d = 279: a KLU refactorisation + solve ~25 us, the condensed ~35 us).
    if (!has_structure_ || structure_.d < kMinCondensedSize) return FallbackFactorize(a);
    const SpMat* source = &a;
    if (!a.isCompressed()) {
      scratch_ = a;
      scratch_.makeCompressed();
      source = &scratch_;
    }
    const SpMat& m = *source;
    if (!AllFinite(m.valuePtr(), m.nonZeros())) {
      message_ = "cholmod: matrix has a non-finite entry";
      return false;
    }
    if (!analysed_ || !SamePattern(m)) {
      jacobian_ = m;
      Analyse();
      analysed_ = true;
    } else {
      std::copy(m.valuePtr(), m.valuePtr() + m.nonZeros(), jacobian_.valuePtr());
    }
    if (!valid_ || !NumericFactorize()) return FallbackFactorize(jacobian_);
    ++stats_.condensed_factorizations;
    factorized_ = true;
    message_.clear();
    return true;
  }

  bool Solve(const Vec& b, Vec* x) override {
    if (x == nullptr) throw std::invalid_argument("cholmod: Solve needs an output vector");
    if (use_fallback_) {
      const bool ok = fallback_->Solve(b, x);
      if (!ok) message_ = fallback_->message();
      return ok;
    }
    if (!factorized_) {
      message_ = "cholmod: Solve called without a successful factorisation";
      return false;
    }
    if (b.size() != jacobian_.rows()) {
      throw std::invalid_argument("cholmod: right-hand side has size " + std::to_string(b.size()) +
                                  ", the matrix has " + std::to_string(jacobian_.rows()) + " rows");
    }
    rhs_ = b;  // b may alias *x
    SolveRefined(rhs_, x);
    if (!(stats_.last_backward_error <= kAcceptBackwardError)) {
      // The condensed answer is not accurate enough: solve this system by the full LU.
      ++stats_.fallback_solves;
      use_fallback_ = true;  // and for the later solves with this matrix
      ++stats_.fallback_factorizations;
      if (!fallback_->Factorize(jacobian_) || !fallback_->Solve(rhs_, x)) {
        message_ = fallback_->message();
        return false;
      }
    }
    if (!x->allFinite()) {
      message_ = "cholmod: the solution has non-finite entries";
      return false;
    }
    return true;
  }

  int num_analyses() const override { return num_analyses_ + fallback_->num_analyses(); }
  int num_full_factorizations() const override {
    return stats_.condensed_factorizations + fallback_->num_full_factorizations();
  }
  const std::string& message() const override { return message_; }
  const CondensedSolverStats& stats() const { return stats_; }

 private:
  bool FallbackFactorize(const SpMat& a) {
    use_fallback_ = true;
    ++stats_.fallback_factorizations;
    const bool ok = fallback_->Factorize(a);
    factorized_ = ok;
    message_ = ok ? std::string() : fallback_->message();
    return ok;
  }

  bool SamePattern(const SpMat& a) const {
    return a.rows() == jacobian_.rows() && a.nonZeros() == jacobian_.nonZeros() &&
           std::memcmp(a.outerIndexPtr(), jacobian_.outerIndexPtr(),
                       sizeof(int) * (a.outerSize() + 1)) == 0 &&
           std::memcmp(a.innerIndexPtr(), jacobian_.innerIndexPtr(), sizeof(int) * a.nonZeros()) ==
               0;
  }

  // Classifies every stored entry of the Jacobian by block (slots into jacobian_'s values),
  // checks the block form, builds the pattern of Kc (lower triangle) and, when that changed,
  // CHOLMOD's symbolic analysis. Sets valid_.
  void Analyse() {
    valid_ = false;
    const SpMat& j = jacobian_;
    const int n = static_cast<int>(j.rows());
    d_ = structure_.d;
    nc_ = structure_.nc;
    m_ = n - d_ - 2 * nc_;
    if (d_ <= 0 || nc_ < 0 || m_ < 0) return;
    const int r2 = d_, r3 = d_ + nc_, r4 = d_ + 2 * nc_;
    const int* outer = j.outerIndexPtr();
    const int* inner = j.innerIndexPtr();

    a_src_.clear();
    std::vector<ScatterPattern::Entry> kc_entries;
    diag_src_.assign(d_, -1);
    std::vector<std::vector<std::pair<int, int>>> g_rows(nc_);  // per pair: (col, slot)
    v_.clear();
    vg_.clear();
    vr_.clear();
    u1_.clear();
    u3_.clear();
    w_.clear();
    e_src_.assign(nc_, -1);
    da_src_.assign(nc_, -1);
    db_src_.assign(nc_, -1);
    std::vector<std::vector<std::pair<int, int>>> h_cols(nc_);  // per pair: (row, slot)
    for (int col = 0; col < n; ++col) {
      for (int k = outer[col]; k < outer[col + 1]; ++k) {
        const int row = inner[k];
        if (col < d_) {  // v columns
          if (row < d_) {
            if (row >= col) {
              a_src_.push_back(k);
              kc_entries.emplace_back(row, col);
              if (row == col) diag_src_[col] = k;
            }
          } else if (row < r3) {
            g_rows[row - r2].emplace_back(col, k);
          } else if (row < r4) {
            return;  // R3 must not depend on v
          } else {
            v_.push_back({row - r4, col, k});
          }
        } else if (col < r3) {  // g columns
          const int p = col - d_;
          if (row == r2 + p) {
            e_src_[p] = k;
          } else if (row == r3 + p) {
            da_src_[p] = k;
          } else if (row >= r4) {
            vg_.push_back({row - r4, p, k});
          } else {
            return;
          }
        } else if (col < r4) {  // r columns
          const int p = col - r3;
          if (row < d_) {
            h_cols[p].emplace_back(row, k);
          } else if (row == r3 + p) {
            db_src_[p] = k;
          } else if (row >= r4) {
            vr_.push_back({row - r4, p, k});
          } else {
            return;
          }
        } else {  // border columns
          const int l = col - r4;
          if (row < d_) {
            u1_.push_back({l, row, k});
          } else if (row >= r3 && row < r4) {
            u3_.push_back({l, row - r3, k});
          } else if (row >= r4) {
            w_.push_back({row - r4, l, k});
          } else {
            return;  // R2 must not depend on y
          }
        }
      }
    }
    // G by pairs (rows sorted by column since the scan is column-major), and H = -coupling G^T
    // must have the same pattern.
    g_start_.assign(nc_ + 1, 0);
    g_col_.clear();
    g_src_.clear();
    h_src_.clear();
    for (int p = 0; p < nc_; ++p) {
      if (e_src_[p] < 0) return;
      if (h_cols[p].size() != g_rows[p].size()) return;
      for (std::size_t q = 0; q < g_rows[p].size(); ++q) {
        if (h_cols[p][q].first != g_rows[p][q].first) return;
        g_col_.push_back(g_rows[p][q].first);
        g_src_.push_back(g_rows[p][q].second);
        h_src_.push_back(h_cols[p][q].second);
      }
      g_start_[p + 1] = static_cast<int>(g_col_.size());
    }
    // Kc = A (lower) + the pair springs G_p^T w_p G_p (lower).
    num_a_entries_ = kc_entries.size();
    for (int p = 0; p < nc_; ++p) {
      for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) {
        for (int t = g_start_[p]; t <= s; ++t) kc_entries.emplace_back(g_col_[s], g_col_[t]);
      }
    }
    const ScatterPattern kc(d_, d_, kc_entries);
    const SpMat& pattern = kc.pattern();
    const bool same_kc =
        kc_lower_.rows() == d_ && kc_lower_.nonZeros() == pattern.nonZeros() &&
        std::equal(pattern.outerIndexPtr(), pattern.outerIndexPtr() + d_ + 1,
                   kc_lower_.outerIndexPtr()) &&
        std::equal(pattern.innerIndexPtr(), pattern.innerIndexPtr() + pattern.nonZeros(),
                   kc_lower_.innerIndexPtr());
    kc_ = pattern;
    kc_slots_ = kc.slots();
    if (!same_kc) {
      // The factorisations belong to the old pattern: analysed again.
      kc_lower_ = pattern;
      FreeFactor();
      AnalyseContactBlock(kc_entries);
    }
    wpair_.resize(nc_);
    ae_.resize(nc_);
    e_.resize(nc_);
    bt_.resize(nc_);
    valid_ = true;
  }

  // The dofs the pairs act on ("contact dofs" c, sorted) and, when they are few, CHOLMOD's
  // analysis of Kc with c ordered last (interior i by CHOLMOD's own ordering of A_ii).
  void AnalyseContactBlock(const std::vector<ScatterPattern::Entry>& kc_entries) {
    c_dofs_.assign(g_col_.begin(), g_col_.end());
    std::sort(c_dofs_.begin(), c_dofs_.end());
    c_dofs_.erase(std::unique(c_dofs_.begin(), c_dofs_.end()), c_dofs_.end());
    const int nc_dofs = static_cast<int>(c_dofs_.size());
    c_index_.assign(d_, -1);
    for (int k = 0; k < nc_dofs; ++k) c_index_[c_dofs_[k]] = k;
    schur_possible_ = false;
    schur_ok_ = false;
    a_cache_.clear();
    if (nc_dofs == 0 || d_ < kSchurMinSize || kSchurMaxFraction * nc_dofs > d_) return;
    const int ni = d_ - nc_dofs;
    // The slots of Kc's diagonal on the contact dofs (every contact dof has one: the s == t
    // terms of the springs).
    kc_cdiag_slot_.assign(nc_dofs, -1);
    for (std::size_t k = num_a_entries_; k < kc_entries.size(); ++k) {
      if (kc_entries[k].first == kc_entries[k].second) {
        kc_cdiag_slot_[c_index_[kc_entries[k].first]] = kc_slots_[k];
      }
    }
    // Interior ordering: CHOLMOD's default analysis of the pattern of A_ii.
    std::vector<int> interior;
    std::vector<int> interior_index(d_, -1);
    for (int j = 0; j < d_; ++j) {
      if (c_index_[j] < 0) {
        interior_index[j] = static_cast<int>(interior.size());
        interior.push_back(j);
      }
    }
    std::vector<Triplet> t;
    for (std::size_t k = 0; k < num_a_entries_; ++k) {
      const int i = interior_index[kc_entries[k].first];
      const int j = interior_index[kc_entries[k].second];
      if (i >= 0 && j >= 0) t.emplace_back(i, j, 1.0);
    }
    for (int i = 0; i < ni; ++i) t.emplace_back(i, i, 1.0);
    SpMat aii(ni, ni);
    aii.setFromTriplets(t.begin(), t.end());
    aii.makeCompressed();
    cholmod_sparse view = LowerView(aii);
    cholmod_factor* interior_symbolic = cholmod_analyze(&view, &common_);
    if (interior_symbolic == nullptr) return;
    std::vector<int> perm(d_);
    const int* ip = static_cast<const int*>(interior_symbolic->Perm);
    for (int k = 0; k < ni; ++k) perm[k] = interior[ip[k]];
    cholmod_free_factor(&interior_symbolic, &common_);
    for (int k = 0; k < nc_dofs; ++k) perm[ni + k] = c_dofs_[k];
    // Kc analysed with exactly this order (no postordering, which could move c) and
    // supernodal, so that the trailing block of L can be read off the supernodes.
    const int nmethods = common_.nmethods, ordering = common_.method[0].ordering;
    const int postorder = common_.postorder, supernodal = common_.supernodal;
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_GIVEN;
    common_.postorder = 0;
    common_.supernodal = CHOLMOD_SUPERNODAL;
    cholmod_sparse kview = KcView();
    ++num_analyses_;
    schur_factor_ = cholmod_analyze_p(&kview, perm.data(), nullptr, 0, &common_);
    common_.nmethods = nmethods;
    common_.method[0].ordering = ordering;
    common_.postorder = postorder;
    common_.supernodal = supernodal;
    if (schur_factor_ == nullptr) return;
    const int* lp = static_cast<const int*>(schur_factor_->Perm);
    if (!std::equal(perm.begin(), perm.end(), lp)) return;
    schur_possible_ = true;
  }

  // Kc = [A_ii A_ic; A_ci A_cc + G^T W G]. While A keeps its values (small deformation: the
  // stiffness is constant), A + D0 (D0 = diag(A) on c, to keep it definite) is factorised once
  // with c last, L = [L_ii 0; L_ci L_cc]; then Kc = [L_ii 0; L_ci I] diag(I, M) [..]^T with the
  // dense M = L_cc L_cc^T - D0 + G^T W G, and a Newton iteration factorises only M.
  bool SchurFactorize() {
    const double* val = jacobian_.valuePtr();
    bool same = schur_factor_->minor == schur_factor_->n && a_cache_.size() == num_a_entries_;
    for (std::size_t k = 0; same && k < num_a_entries_; ++k) same = val[a_src_[k]] == a_cache_[k];
    const int nc_dofs = static_cast<int>(c_dofs_.size());
    if (!same) {
      if (!a_cache_.empty()) {
        // A changed: a tangent stiffness. Refactorising the big factor every iteration would
        // cost as much as the plain path, with a worse ordering: use the plain path.
        schur_possible_ = false;
        return false;
      }
      a_cache_.resize(num_a_entries_);
      for (std::size_t k = 0; k < num_a_entries_; ++k) a_cache_[k] = val[a_src_[k]];
      schur_ok_ = false;
      double* kv = kc_.valuePtr();
      std::fill(kv, kv + kc_.nonZeros(), 0.0);
      for (std::size_t k = 0; k < num_a_entries_; ++k) kv[kc_slots_[k]] += val[a_src_[k]];
      d0_.resize(nc_dofs);
      for (int k = 0; k < nc_dofs; ++k) {
        const int src = diag_src_[c_dofs_[k]];
        const double a = src >= 0 ? std::abs(val[src]) : 0.0;
        d0_[k] = a > 0.0 ? a : 1.0;
        kv[kc_cdiag_slot_[k]] += d0_[k];
      }
      cholmod_sparse view = KcView();
      if (!cholmod_factorize(&view, schur_factor_, &common_) || common_.status != CHOLMOD_OK ||
          schur_factor_->minor < schur_factor_->n || !schur_factor_->is_super) {
        return false;
      }
      // L_cc from the supernodes (columns and rows >= ni, in the order of c).
      const int ni = d_ - nc_dofs;
      l_cc_.setZero(nc_dofs, nc_dofs);
      const int* super = static_cast<const int*>(schur_factor_->super);
      const int* pi = static_cast<const int*>(schur_factor_->pi);
      const int* px = static_cast<const int*>(schur_factor_->px);
      const int* rows = static_cast<const int*>(schur_factor_->s);
      const double* lx = static_cast<const double*>(schur_factor_->x);
      for (std::size_t k = 0; k < schur_factor_->nsuper; ++k) {
        const int k1 = super[k], k2 = super[k + 1];
        if (k2 <= ni) continue;
        const int nsrow = pi[k + 1] - pi[k];
        for (int col = std::max(k1, ni); col < k2; ++col) {
          const double* column = lx + px[k] + static_cast<std::ptrdiff_t>(col - k1) * nsrow;
          for (int q = col - k1; q < nsrow; ++q) {
            l_cc_(rows[pi[k] + q] - ni, col - ni) = column[q];
          }
        }
      }
      s_cc_.noalias() = l_cc_.triangularView<Eigen::Lower>() * l_cc_.transpose();
      s_cc_.diagonal() -= d0_;
      schur_ok_ = true;
      ++schur_generation_;
    }
    if (!schur_ok_) return false;
    m_cc_ = s_cc_;
    for (int p = 0; p < nc_; ++p) {
      const double w = wpair_[p];
      for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) {
        const double ws = w * val[g_src_[s]];
        const int cs = c_index_[g_col_[s]];
        for (int t = g_start_[p]; t <= s; ++t)
          m_cc_(cs, c_index_[g_col_[t]]) += ws * val[g_src_[t]];
      }
    }
    m_llt_.compute(m_cc_);
    return m_llt_.info() == Eigen::Success;
  }

  // The plain path: Kc assembled and factorised by CHOLMOD with its own ordering.
  bool PlainFactorize() {
    const double* val = jacobian_.valuePtr();
    double* kv = kc_.valuePtr();
    std::fill(kv, kv + kc_.nonZeros(), 0.0);
    std::size_t k = 0;
    for (; k < num_a_entries_; ++k) kv[kc_slots_[k]] += val[a_src_[k]];
    for (int p = 0; p < nc_; ++p) {
      const double w = wpair_[p];
      for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) {
        const double ws = w * val[g_src_[s]];
        for (int t = g_start_[p]; t <= s; ++t) kv[kc_slots_[k++]] += ws * val[g_src_[t]];
      }
    }
    cholmod_sparse view = KcView();
    if (factor_ == nullptr) {
      ++num_analyses_;
      factor_ = cholmod_analyze(&view, &common_);
      if (factor_ == nullptr) return false;
    }
    return cholmod_factorize(&view, factor_, &common_) && common_.status == CHOLMOD_OK &&
           factor_->minor == factor_->n;
  }

  static cholmod_sparse LowerView(SpMat& m) {
    cholmod_sparse s{};
    s.nrow = static_cast<std::size_t>(m.rows());
    s.ncol = static_cast<std::size_t>(m.cols());
    s.nzmax = static_cast<std::size_t>(m.nonZeros());
    s.p = m.outerIndexPtr();
    s.i = m.innerIndexPtr();
    s.x = m.valuePtr();
    s.stype = -1;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }

  cholmod_sparse KcView() {
    cholmod_sparse s{};
    s.nrow = s.ncol = static_cast<std::size_t>(d_);
    s.nzmax = static_cast<std::size_t>(kc_.nonZeros());
    s.p = kc_.outerIndexPtr();
    s.i = kc_.innerIndexPtr();
    s.x = kc_.valuePtr();
    s.stype = -1;  // lower triangle stored
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }

  // Kc, its factorisation, and the border's Schur complement at the current values.
  bool NumericFactorize() {
    const double* val = jacobian_.valuePtr();
    const double coupling = structure_.coupling;
    double max_diag = 0.0;
    for (int i = 0; i < d_; ++i) {
      if (diag_src_[i] >= 0) max_diag = std::max(max_diag, std::abs(val[diag_src_[i]]));
    }
    if (!(max_diag > 0.0)) max_diag = 1.0;
    stats_.capped_pairs = 0;
    for (int p = 0; p < nc_; ++p) {
      const double e = val[e_src_[p]];
      const double da = da_src_[p] >= 0 ? val[da_src_[p]] : 0.0;
      const double db = db_src_[p] >= 0 ? val[db_src_[p]] : 0.0;
      if (e == 0.0 || (da == 0.0 && db == 0.0)) return false;
      // H = -coupling G^T: checked, since the condensed matrix assumes it.
      double stiffness = 0.0, g2 = 0.0;
      for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) {
        const double g = val[g_src_[s]];
        const double h = val[h_src_[s]];
        if (!(std::abs(h + coupling * g) <= 1e-10 * std::abs(h))) return false;
        g2 = std::max(g2, g * g);
        const int dof = g_col_[s];
        if (diag_src_[dof] >= 0) stiffness = std::max(stiffness, std::abs(val[diag_src_[dof]]));
      }
      if (!(stiffness > 0.0)) stiffness = max_diag;
      const double cap = g2 > 0.0 ? kPenaltyCap * stiffness / g2 : 0.0;
      double w = db != 0.0 ? -coupling * da / (e * db) : std::numeric_limits<double>::infinity();
      double bt = db;
      if (g2 > 0.0 && std::abs(w) > cap) {
        if (w < 0.0 || da == 0.0) return false;  // a huge negative spring: not for Cholesky
        w = cap;
        bt = -coupling * da / (e * w);
        ++stats_.capped_pairs;
      } else if (db == 0.0) {
        return false;  // a pair on no dof with Db = 0: r is undetermined here
      }
      wpair_[p] = w;
      e_[p] = e;
      ae_[p] = da / e;
      bt_[p] = bt;
    }
    UpdateJacobianNorm();
    schur_active_ = schur_possible_ && SchurFactorize();
    if (schur_active_) ++stats_.contact_block_factorizations;
    if (!schur_active_ && !PlainFactorize()) return false;  // not positive definite
    // Border: B = U1 - H Db~^-1 U3, C = V - G^T (E^-1 Vg) + G^T (Da E^-1 Db~^-1 Vr),
    // Wc = W - Vr^T Db~^-1 U3, then Z = Kc^-1 B and S = Wc - C^T Z.
    u3_dense_.setZero(nc_, m_);
    vg_dense_.setZero(nc_, m_);
    vr_dense_.setZero(nc_, m_);
    for (const auto& t : u3_) u3_dense_(t.b, t.a) += val[t.src];
    for (const auto& t : vg_) vg_dense_(t.b, t.a) += val[t.src];
    for (const auto& t : vr_) vr_dense_(t.b, t.a) += val[t.src];
    border_b_.setZero(d_, m_);
    border_c_.setZero(d_, m_);
    Mat wc = Mat::Zero(m_, m_);
    for (const auto& t : u1_) border_b_(t.b, t.a) += val[t.src];
    for (const auto& t : v_) border_c_(t.b, t.a) += val[t.src];
    for (const auto& t : w_) wc(t.a, t.b) += val[t.src];
    for (int p = 0; p < nc_; ++p) {
      for (int l = 0; l < m_; ++l) {
        const double q = u3_dense_(p, l) / bt_[p];
        if (q != 0.0) {
          for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) {
            border_b_(g_col_[s], l) -= val[h_src_[s]] * q;
          }
          for (int kk = 0; kk < m_; ++kk) wc(kk, l) -= vr_dense_(p, kk) * q;
        }
        const double c = -vg_dense_(p, l) / e_[p] + vr_dense_(p, l) * ae_[p] / bt_[p];
        if (c != 0.0) {
          for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) {
            border_c_(g_col_[s], l) += c * val[g_src_[s]];
          }
        }
      }
    }
    if (m_ > 0 && schur_active_) {
      // Kc = Lt Dt Lt^T (Lt = [L_ii 0; L_ci I] permuted, Dt = diag(I, M)): then
      // C^T Kc^-1 B = (Lt^-1 C)^T Dt^-1 (Lt^-1 B), forward halves only. The forward solve of
      // U1 (the load column) is kept while the big factor is; the parts on the contact dofs
      // need none (Lt^-1 [0; v_c] = [0; v_c]).
      Mat u1 = Mat::Zero(d_, m_), v = Mat::Zero(d_, m_);
      for (const auto& t : u1_) u1(t.b, t.a) += val[t.src];
      for (const auto& t : v_) v(t.b, t.a) += val[t.src];
      if (!(u1_generation_ == schur_generation_ && u1 == u1_cached_)) {
        u1_cached_ = u1;
        if (!Forward(u1, &fwd_u1_)) return false;
        u1_generation_ = schur_generation_;
      }
      fwd_b_ = fwd_u1_;
      if (v.isZero(0.0)) {
        fwd_c_.setZero(d_, m_);
      } else if (!Forward(v, &fwd_c_)) {
        return false;
      }
      const int ni = d_ - static_cast<int>(c_dofs_.size());
      for (std::size_t k = 0; k < c_dofs_.size(); ++k) {
        const int dof = c_dofs_[k];
        fwd_b_.row(ni + k) += border_b_.row(dof) - u1.row(dof);
        fwd_c_.row(ni + k) += border_c_.row(dof) - v.row(dof);
      }
      dfwd_b_ = fwd_b_;
      ApplyDinv(&dfwd_b_);
      const Mat schur = wc - fwd_c_.transpose() * dfwd_b_;
      if (!schur.allFinite()) return false;
      schur_lu_.compute(schur);
      if (schur_lu_.rank() < m_) return false;
    } else if (m_ > 0) {
      if (!CholmodSolve(border_b_, &border_z_)) return false;
      const Mat schur = wc - border_c_.transpose() * border_z_;
      if (!schur.allFinite()) return false;
      schur_lu_.compute(schur);
      if (schur_lu_.rank() < m_) return false;
    }
    return true;
  }

  // x = Kc^-1 b (b: d x k), by the plain factor or by the contact-block factorisation.
  bool KcSolve(const double* b, int cols, double* x) {
    const std::size_t size = sizeof(double) * static_cast<std::size_t>(d_) * cols;
    if (!schur_active_) {
      if (!Phase(CHOLMOD_A, factor_, b, cols, &x1_)) return false;
      std::memcpy(x, x1_->x, size);
      return true;
    }
    // P, L^-1; on the c part y_c -> L_cc^T M^-1 L_cc y_c; L^-T, P^T.
    if (!Phase(CHOLMOD_P, schur_factor_, b, cols, &x1_) ||
        !Phase(CHOLMOD_L, schur_factor_, static_cast<const double*>(x1_->x), cols, &x2_)) {
      return false;
    }
    const int nc_dofs = static_cast<int>(c_dofs_.size());
    const int ni = d_ - nc_dofs;
    for (int col = 0; col < cols; ++col) {
      double* yc = static_cast<double*>(x2_->x) + static_cast<std::ptrdiff_t>(col) * x2_->d + ni;
      Eigen::Map<Vec> ycv(yc, nc_dofs);
      work_c_.noalias() = l_cc_.triangularView<Eigen::Lower>() * ycv;
      m_llt_.solveInPlace(work_c_);
      ycv.noalias() = l_cc_.transpose().triangularView<Eigen::Upper>() * work_c_;
    }
    if (!Phase(CHOLMOD_Lt, schur_factor_, static_cast<const double*>(x2_->x), cols, &x1_) ||
        !Phase(CHOLMOD_Pt, schur_factor_, static_cast<const double*>(x1_->x), cols, &x2_)) {
      return false;
    }
    std::memcpy(x, x2_->x, size);
    return true;
  }
  // One CHOLMOD solve phase (sys) of `factor` on the d x cols column-major block `in`, which
  // CHOLMOD reads through a view (no copy).
  bool Phase(int sys, cholmod_factor* factor, const double* in, int cols, cholmod_dense** out) {
    cholmod_dense rhs{};
    rhs.nrow = static_cast<std::size_t>(d_);
    rhs.ncol = static_cast<std::size_t>(cols);
    rhs.nzmax = rhs.nrow * rhs.ncol;
    rhs.d = rhs.nrow;
    rhs.x = const_cast<double*>(in);
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    return cholmod_solve2(sys, factor, &rhs, nullptr, out, nullptr, &y_, &e_work_, &common_) != 0;
  }
  // Lt^-1 P b (permuted order): P, L^-1, then y_c -> L_cc y_c.
  bool Forward(const Mat& b, Mat* out) {
    if (!Phase(CHOLMOD_P, schur_factor_, b.data(), static_cast<int>(b.cols()), &x1_)) return false;
    if (!Phase(CHOLMOD_L, schur_factor_, static_cast<const double*>(x1_->x),
               static_cast<int>(b.cols()), &x2_)) {
      return false;
    }
    out->resize(d_, b.cols());
    std::memcpy(out->data(), x2_->x, sizeof(double) * out->size());
    const int nc_dofs = static_cast<int>(c_dofs_.size());
    auto tail = out->bottomRows(nc_dofs);
    tail = (l_cc_.triangularView<Eigen::Lower>() * tail).eval();
    return true;
  }
  // Dt^-1 on a permuted block: M^-1 on the contact part.
  void ApplyDinv(Mat* v) const {
    const int nc_dofs = static_cast<int>(c_dofs_.size());
    Mat tail = v->bottomRows(nc_dofs);
    m_llt_.solveInPlace(tail);
    v->bottomRows(nc_dofs) = tail;
  }
  // P^T Lt^-T w: y_c -> L_cc^T y_c, L^-T, P^T.
  bool Backward(Mat w, Mat* out) {
    const int nc_dofs = static_cast<int>(c_dofs_.size());
    auto tail = w.bottomRows(nc_dofs);
    tail = (l_cc_.transpose().triangularView<Eigen::Upper>() * tail).eval();
    if (!Phase(CHOLMOD_Lt, schur_factor_, w.data(), static_cast<int>(w.cols()), &x1_)) return false;
    if (!Phase(CHOLMOD_Pt, schur_factor_, static_cast<const double*>(x1_->x),
               static_cast<int>(w.cols()), &x2_)) {
      return false;
    }
    out->resize(d_, w.cols());
    std::memcpy(out->data(), x2_->x, sizeof(double) * out->size());
    return true;
  }

  bool CholmodSolve(const Mat& b, Mat* x) {
    x->resize(b.rows(), b.cols());
    return KcSolve(b.data(), static_cast<int>(b.cols()), x->data());
  }
  bool CholmodSolve(const Vec& b, Vec* x) {
    x->resize(b.size());
    return KcSolve(b.data(), 1, x->data());
  }

  // One condensed solve of J x = b (J with Db~ in place of Db).
  bool CondensedSolve(const Vec& b, Vec* x) {
    const double* val = jacobian_.valuePtr();
    const int r2 = d_, r3 = d_ + nc_, r4 = d_ + 2 * nc_;
    t_.resize(nc_);
    h1_ = b.head(d_);
    for (int p = 0; p < nc_; ++p) {
      const double t = (b[r3 + p] - ae_[p] * b[r2 + p]) / bt_[p];
      t_[p] = t;
      if (t != 0.0) {
        for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) h1_[g_col_[s]] -= val[h_src_[s]] * t;
      }
    }
    x->resize(b.size());
    if (schur_active_) {
      // f = Lt^-1 h1, y from the Schur complement, v = Kc^-1 (h1 - B y) = Lt^-T Dt^-1 (f - Fb y):
      // one forward and one backward solve.
      if (!Forward(h1_, &fwd_h_)) return false;
      ApplyDinv(&fwd_h_);
      if (m_ > 0) {
        Vec h4 = b.tail(m_);
        for (int p = 0; p < nc_; ++p) {
          const double b2e = b[r2 + p] / e_[p];
          for (int k = 0; k < m_; ++k) h4[k] -= vg_dense_(p, k) * b2e + vr_dense_(p, k) * t_[p];
        }
        h4.noalias() -= fwd_c_.transpose() * fwd_h_.col(0);
        const Vec y = schur_lu_.solve(h4);
        fwd_h_.col(0).noalias() -= dfwd_b_ * y;
        x->tail(m_) = y;
      }
      if (!Backward(fwd_h_, &zmat_)) return false;
      z_ = zmat_.col(0);
    } else if (!CholmodSolve(h1_, &z_)) {
      return false;
    }
    if (m_ > 0 && !schur_active_) {
      Vec h4 = b.tail(m_);
      for (int p = 0; p < nc_; ++p) {
        const double b2e = b[r2 + p] / e_[p];
        for (int k = 0; k < m_; ++k) h4[k] -= vg_dense_(p, k) * b2e + vr_dense_(p, k) * t_[p];
      }
      h4.noalias() -= border_c_.transpose() * z_;
      const Vec y = schur_lu_.solve(h4);
      z_.noalias() -= border_z_ * y;
      x->tail(m_) = y;
    }
    x->head(d_) = z_;
    for (int p = 0; p < nc_; ++p) {
      double gv = 0.0;
      for (int s = g_start_[p]; s < g_start_[p + 1]; ++s) gv += val[g_src_[s]] * z_[g_col_[s]];
      const double g = (b[r2 + p] - gv) / e_[p];
      double rhs = b[r3 + p] - e_[p] * ae_[p] * g;
      for (int l = 0; l < m_; ++l) rhs -= u3_dense_(p, l) * (*x)[r4 + l];
      (*x)[r2 + p] = g;
      (*x)[r3 + p] = rhs / bt_[p];
    }
    return true;
  }

  // res = b - J x with the full matrix; returns ||res||_inf.
  double Residual(const Vec& b, const Vec& x, Vec* res) const {
    *res = b;
    const int* outer = jacobian_.outerIndexPtr();
    const int* inner = jacobian_.innerIndexPtr();
    const double* val = jacobian_.valuePtr();
    for (int col = 0; col < jacobian_.cols(); ++col) {
      const double xc = x[col];
      if (xc == 0.0) continue;
      for (int k = outer[col]; k < outer[col + 1]; ++k) (*res)[inner[k]] -= val[k] * xc;
    }
    return res->size() == 0 ? 0.0 : res->cwiseAbs().maxCoeff();
  }

  // Condensed solve with iterative refinement on the full system; leaves the backward error in
  // stats_.last_backward_error (infinite when a solve failed).
  void SolveRefined(const Vec& b, Vec* x) {
    stats_.last_backward_error = std::numeric_limits<double>::infinity();
    if (!CondensedSolve(b, x)) return;
    const double b_norm = b.size() == 0 ? 0.0 : b.cwiseAbs().maxCoeff();
    auto backward = [&](double res_norm, const Vec& xv) {
      const double scale = jacobian_norm_ * xv.cwiseAbs().maxCoeff() + b_norm;
      return scale > 0.0 ? res_norm / scale : 0.0;
    };
    double omega = backward(Residual(b, *x, &res_), *x);
    for (int sweep = 0; sweep < kMaxRefinements && omega > kTargetBackwardError; ++sweep) {
      if (!CondensedSolve(res_, &dx_)) break;
      ++stats_.refinement_sweeps;
      trial_ = *x + dx_;
      const double next = backward(Residual(b, trial_, &res_trial_), trial_);
      if (!(next < omega)) break;
      const bool slow = next > 0.5 * omega;
      x->swap(trial_);
      res_.swap(res_trial_);
      omega = next;
      if (slow) break;
    }
    stats_.last_backward_error = omega;
  }

  // ||J||_inf, for the backward error of the refinement.
  void UpdateJacobianNorm() {
    row_abs_.setZero(jacobian_.rows());
    const int* inner = jacobian_.innerIndexPtr();
    const double* val = jacobian_.valuePtr();
    for (Eigen::Index k = 0; k < jacobian_.nonZeros(); ++k) row_abs_[inner[k]] += std::abs(val[k]);
    jacobian_norm_ = row_abs_.size() == 0 ? 0.0 : row_abs_.maxCoeff();
  }

  void FreeFactor() {
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    if (schur_factor_ != nullptr) cholmod_free_factor(&schur_factor_, &common_);
    schur_possible_ = false;
    schur_active_ = false;
  }

  struct Entry {  // (a, b) indices and the slot in the Jacobian's values
    int a;
    int b;
    int src;
  };

  std::unique_ptr<LinearSolver> fallback_;
  JacobianStructure structure_;
  bool has_structure_ = false;
  bool analysed_ = false;
  bool valid_ = false;
  bool factorized_ = false;
  bool use_fallback_ = false;
  int num_analyses_ = 0;
  std::string message_;
  CondensedSolverStats stats_;

  // The Jacobian (private copy: refinement needs its values after Factorize) and its blocks.
  SpMat jacobian_, scratch_;
  int d_ = 0, nc_ = 0, m_ = 0;
  std::vector<int> a_src_, diag_src_, e_src_, da_src_, db_src_;
  std::vector<int> g_start_, g_col_, g_src_, h_src_;
  std::vector<Entry> v_, vg_, vr_, u1_, u3_, w_;  // v_: (row, col); vg_/vr_: (row, pair);
                                                  // u1_: (col, row); u3_: (col, pair); w_
  std::size_t num_a_entries_ = 0;
  std::vector<int> kc_slots_;
  SpMat kc_lower_;  // the pattern of Kc (lower triangle), to detect a change
  SpMat kc_;        // Kc (lower triangle) with its values

  // The contact-block factorisation (SchurFactorize).
  std::vector<int> c_dofs_, c_index_, kc_cdiag_slot_;
  bool schur_possible_ = false;  // analysed, and A has not changed values since
  bool schur_ok_ = false;        // the factor of A + D0 and S_cc are valid for a_cache_
  bool schur_active_ = false;    // the last factorisation used it
  std::vector<double> a_cache_;
  Vec d0_, work_c_;
  Mat l_cc_, s_cc_, m_cc_;
  Eigen::LLT<Mat> m_llt_;
  int schur_generation_ = 0;  // counts factorisations of the big contact-block factor
  int u1_generation_ = -1;    // the generation fwd_u1_ belongs to
  Mat u1_cached_, fwd_u1_, fwd_b_, fwd_c_, dfwd_b_, fwd_h_, zmat_;

  // Numeric data of the last factorisation.
  std::vector<double> wpair_, ae_, e_, bt_;
  Mat u3_dense_, vg_dense_, vr_dense_, border_b_, border_c_, border_z_;
  Eigen::FullPivLU<Mat> schur_lu_;
  double jacobian_norm_ = 0.0;  // ||J||_inf, for the backward error

  // Work storage.
  Vec rhs_, h1_, z_, t_, res_, res_trial_, dx_, trial_, row_abs_;

  cholmod_common common_;
  cholmod_factor* factor_ = nullptr;
  cholmod_factor* schur_factor_ = nullptr;
  cholmod_dense* x1_ = nullptr;
  cholmod_dense* x2_ = nullptr;
  cholmod_dense* y_ = nullptr;
  cholmod_dense* e_work_ = nullptr;
};

}  // namespace

std::unique_ptr<LinearSolver> MakeCondensedCholeskySolver(std::unique_ptr<LinearSolver> fallback) {
  return std::make_unique<CondensedCholeskySolver>(std::move(fallback));
}

const CondensedSolverStats* CondensedStats(const LinearSolver& solver) {
  const auto* s = dynamic_cast<const CondensedCholeskySolver*>(&solver);
  return s != nullptr ? &s->stats() : nullptr;
}

}  // namespace cb

#else  // no SuiteSparse

namespace cb {
std::unique_ptr<LinearSolver> MakeCondensedCholeskySolver(std::unique_ptr<LinearSolver> fallback) {
  return fallback;
}
const CondensedSolverStats* CondensedStats(const LinearSolver& /*solver*/) { return nullptr; }
}  // namespace cb

#endif
