#include "solvers/condensed_cholesky.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/abandonable_work.h"
#include "core/finite.h"
#include "core/slow_work.h"
#include "core/sparse.h"
#include "solvers/condensed_system.h"
#include "solvers/jacobian_blocks.h"

namespace cb {
namespace {

constexpr int kMaxRefinements = 8;
// Systems with fewer dofs d go to the fallback LU.
constexpr int kMinCondensedSize = 1000;
// Refinement stops below this normwise backward error (about 450 ulps: a Newton step needs far
// less, and a sweep costs a whole solve; docs/linear-solvers.md) ...
constexpr double kTargetBackwardError = 1e-13;
// ... and the answer is accepted at or below this one; otherwise the LU solves the system.
constexpr double kAcceptBackwardError = 1e-12;

class CondensedCholeskySolver final : public LinearSolver {
 public:
  explicit CondensedCholeskySolver(std::unique_ptr<LinearSolver> fallback)
      : fallback_(std::move(fallback)) {}

  std::string name() const override { return "cholmod"; }

  void SetStructure(const JacobianStructure* s) override {
    if (s == nullptr) {
      has_structure_ = false;
      return;
    }
    if (!has_structure_ || s->d != structure_.d || s->nc != structure_.nc ||
        s->coupling != structure_.coupling || s->dense_stiffness != structure_.dense_stiffness) {
      analysed_ = false;
    }
    structure_ = *s;
    has_structure_ = true;
  }

  bool Factorize(const SpMat& a) override {
    CheckSquare(a, "cholmod");
    factorized_ = false;
    use_fallback_ = false;
    // Small sparse systems go to the LU: there its refactorisation beats the condensation's
    // fixed costs (docs/linear-solvers.md, "cholmod"); a dense A does not.
    if (!has_structure_ || (structure_.d < kMinCondensedSize && !structure_.dense_stiffness)) {
      return FallbackFactorize(a);
    }
    const SpMat& m = Compressed(a, &uncompressed_scratch_);
    if (!AllFinite(m.valuePtr(), m.nonZeros())) {
      message_ = "cholmod: matrix has a non-finite entry";
      return false;
    }
    if (!analysed_ || !SamePattern(m)) {
      jacobian_ = m;
      AnalysePattern();
      analysed_ = true;
    } else {
      std::copy(m.valuePtr(), m.valuePtr() + m.nonZeros(), jacobian_.valuePtr());
    }
    const bool condensed = has_block_form_ && FactorizeCondensed();
    if (!condensed && has_block_form_ && condensed_.interrupted()) {
      // Abandoned on an interrupt (interruptible_cholmod.h): no fall-back to start.
      message_ = "cholmod: factorisation of a " + std::to_string(m.rows()) + " x " +
                 std::to_string(m.cols()) + " matrix abandoned on an interrupt";
      return false;
    }
    if (!condensed) return FallbackFactorize(jacobian_);
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
      ReportLargeFallback(jacobian_);
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

  int num_analyses() const override {
    return condensed_.num_analyses() + fallback_->num_analyses();
  }
  int num_full_factorizations() const override {
    return stats_.condensed_factorizations + fallback_->num_full_factorizations();
  }
  const std::string& message() const override { return message_; }
  // Only the fallback LU tells a singular matrix (the condensed route falls back on failure).
  bool singular() const override { return use_fallback_ && fallback_->singular(); }
  const CondensedSolverStats& stats() const { return stats_; }

 private:
  bool FallbackFactorize(const SpMat& a) {
    use_fallback_ = true;
    ++stats_.fallback_factorizations;
    ReportLargeFallback(a);
    const bool ok = fallback_->Factorize(a);
    factorized_ = ok;
    message_ = ok ? std::string() : fallback_->message();
    return ok;
  }

  // A fall-back factorisation of a large matrix may cost minutes (a 3-D system's fill): the
  // program is told before it starts (core/slow_work.h).
  void ReportLargeFallback(const SpMat& a) const {
    if (a.nonZeros() < kAbandonableMinNonZeros) return;
    ReportSlowWork({name(), fallback_->name(), a.rows(), a.nonZeros()});
  }

  bool SamePattern(const SpMat& a) const {
    return a.rows() == jacobian_.rows() && a.nonZeros() == jacobian_.nonZeros() &&
           std::memcmp(a.outerIndexPtr(), jacobian_.outerIndexPtr(),
                       sizeof(int) * (a.outerSize() + 1)) == 0 &&
           std::memcmp(a.innerIndexPtr(), jacobian_.innerIndexPtr(), sizeof(int) * a.nonZeros()) ==
               0;
  }

  // The blocks of jacobian_'s pattern, handed to the condensed system; has_block_form_ says
  // whether there are any.
  void AnalysePattern() {
    has_block_form_ = false;
    std::optional<JacobianBlocks> blocks =
        FindJacobianBlocks(jacobian_, structure_.d, structure_.nc);
    if (!blocks) return;
    condensed_.Analyse(std::move(*blocks));
    has_block_form_ = true;
  }

  bool FactorizeCondensed() {
    const bool ok = condensed_.Factorize(jacobian_.valuePtr(), structure_.coupling);
    stats_.capped_pairs = condensed_.capped_pairs();
    if (condensed_.used_contact_block()) ++stats_.contact_block_factorizations;
    if (ok) UpdateJacobianNorm();
    return ok;
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
    const double* values = jacobian_.valuePtr();
    if (!condensed_.Solve(values, b, x)) return;
    const double b_norm = b.size() == 0 ? 0.0 : b.cwiseAbs().maxCoeff();
    auto backward = [&](double res_norm, const Vec& xv) {
      const double scale = jacobian_norm_ * xv.cwiseAbs().maxCoeff() + b_norm;
      return scale > 0.0 ? res_norm / scale : 0.0;
    };
    double omega = backward(Residual(b, *x, &residual_), *x);
    for (int sweep = 0; sweep < kMaxRefinements && omega > kTargetBackwardError; ++sweep) {
      if (!condensed_.Solve(values, residual_, &correction_)) break;
      ++stats_.refinement_sweeps;
      trial_ = *x + correction_;
      const double next = backward(Residual(b, trial_, &trial_residual_), trial_);
      if (!(next < omega)) break;
      const bool slow = next > 0.5 * omega;
      x->swap(trial_);
      residual_.swap(trial_residual_);
      omega = next;
      if (slow) break;
    }
    stats_.last_backward_error = omega;
  }

  // ||J||_inf, for the backward error of the refinement.
  void UpdateJacobianNorm() {
    row_abs_sums_.setZero(jacobian_.rows());
    const int* inner = jacobian_.innerIndexPtr();
    const double* val = jacobian_.valuePtr();
    for (Eigen::Index k = 0; k < jacobian_.nonZeros(); ++k) {
      row_abs_sums_[inner[k]] += std::abs(val[k]);
    }
    jacobian_norm_ = row_abs_sums_.size() == 0 ? 0.0 : row_abs_sums_.maxCoeff();
  }

  std::unique_ptr<LinearSolver> fallback_;
  JacobianStructure structure_;
  bool has_structure_ = false;
  bool analysed_ = false;        // jacobian_'s pattern is analysed for structure_
  bool has_block_form_ = false;  // ... and has the block form
  bool factorized_ = false;
  bool use_fallback_ = false;
  std::string message_;
  CondensedSolverStats stats_;

  // The Jacobian (a private copy: refinement needs its values after Factorize).
  SpMat jacobian_, uncompressed_scratch_;
  double jacobian_norm_ = 0.0;  // ||J||_inf, for the backward error
  CondensedSystem condensed_;

  // Work storage of the refinement.
  Vec rhs_, residual_, trial_residual_, correction_, trial_, row_abs_sums_;
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
