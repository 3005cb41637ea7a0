#include "solvers/linear_solver.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
#include <Eigen/KLUSupport>
#include <Eigen/UmfPackSupport>
#endif

namespace cb {
namespace {

// The part every backend shares: argument checks, a private copy of the matrix, and the
// decision whether the symbolic analysis must be redone.
//
// The copy exists for two reasons. Eigen's UMFPACK wrapper keeps a reference to the factorised
// matrix and reads it again in every solve (iterative refinement), so a caller that refills or
// destroys its matrix between Factorize and Solve would otherwise corrupt the solve. And the
// copy's index arrays are exactly the "previous pattern" we compare against. Copying into the
// same storage costs O(nnz) and allocates nothing while the pattern is unchanged, which is
// negligible next to a numerical factorisation.
class PatternTrackingSolver : public LinearSolver {
 public:
  bool Factorize(const SpMat& a) final {
    if (a.rows() != a.cols()) {
      throw std::invalid_argument(name() + ": Factorize needs a square matrix, got " +
                                  std::to_string(a.rows()) + " x " + std::to_string(a.cols()));
    }
    factorized_ = false;
    const SpMat* source = &a;
    if (!a.isCompressed()) {
      // Rare (a caller that inserted without makeCompressed); the comparison below and the
      // backends need the standard compressed arrays.
      uncompressed_scratch_ = a;
      uncompressed_scratch_.makeCompressed();
      source = &uncompressed_scratch_;
    }
    const SpMat& m = *source;
    const double* values = m.valuePtr();
    for (Eigen::Index k = 0; k < m.nonZeros(); ++k) {
      if (!std::isfinite(values[k])) {
        message_ = name() + ": matrix has a non-finite entry (value " + std::to_string(values[k]) +
                   " at storage position " + std::to_string(k) + ")";
        return false;
      }
    }
    const bool pattern_changed = !analysed_ || !SamePattern(m, matrix_);
    matrix_ = m;
    if (pattern_changed) {
      analysed_ = false;
      ++num_analyses_;
      if (!Analyze(matrix_, &message_)) return false;
      analysed_ = true;
    }
    if (!NumericFactorize(matrix_, &message_)) return false;
    factorized_ = true;
    message_.clear();
    return true;
  }

  bool Solve(const Vec& b, Vec* x) final {
    if (x == nullptr) throw std::invalid_argument(name() + ": Solve needs an output vector");
    if (!factorized_) {
      message_ = name() + ": Solve called without a successful factorisation";
      return false;
    }
    if (b.size() != matrix_.rows()) {
      throw std::invalid_argument(name() + ": right-hand side has size " +
                                  std::to_string(b.size()) + ", the matrix has " +
                                  std::to_string(matrix_.rows()) + " rows");
    }
    // The backends read b while writing x; an aliased call goes through a private copy.
    const Vec* rhs = &b;
    if (x == &b) {
      rhs_ = b;
      rhs = &rhs_;
    }
    if (!BackSolve(*rhs, x, &message_)) return false;
    if (!x->allFinite()) {
      message_ = name() + ": the solution has non-finite entries (matrix numerically singular)";
      return false;
    }
    return true;
  }

  int num_analyses() const final { return num_analyses_; }
  const std::string& message() const final { return message_; }

 protected:
  // Symbolic analysis (ordering) of the pattern of `a`.
  virtual bool Analyze(const SpMat& a, std::string* why) = 0;
  // Numerical factorisation of `a`, whose pattern was analysed.
  virtual bool NumericFactorize(const SpMat& a, std::string* why) = 0;
  virtual bool BackSolve(const Vec& b, Vec* x, std::string* why) = 0;

 private:
  static bool SamePattern(const SpMat& a, const SpMat& b) {
    if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) {
      return false;
    }
    return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1,
                      b.outerIndexPtr()) &&
           std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
  }

  SpMat matrix_;
  SpMat uncompressed_scratch_;
  Vec rhs_;
  bool analysed_ = false;
  bool factorized_ = false;
  int num_analyses_ = 0;
  std::string message_;
};

// Eigen's supernodal SparseLU with a COLAMD column ordering (partial pivoting). It detects only
// exactly zero pivots; a nearly singular matrix shows up as a huge or non-finite solution.
class EigenSparseLuSolver final : public PatternTrackingSolver {
 public:
  std::string name() const override { return "sparse-lu"; }

 protected:
  bool Analyze(const SpMat& a, std::string* /*why*/) override {
    lu_.analyzePattern(a);
    return true;
  }
  bool NumericFactorize(const SpMat& a, std::string* why) override {
    lu_.factorize(a);
    if (lu_.info() != Eigen::Success) {
      *why = "sparse-lu: factorisation failed (singular matrix): " + lu_.lastErrorMessage();
      return false;
    }
    return true;
  }
  bool BackSolve(const Vec& b, Vec* x, std::string* why) override {
    *x = lu_.solve(b);
    if (lu_.info() != Eigen::Success) {
      *why = "sparse-lu: solve failed";
      return false;
    }
    return true;
  }

 private:
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> lu_;
};

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

// UMFPACK (multifrontal LU with its own column ordering, scaling and iterative refinement).
class UmfpackSolver final : public PatternTrackingSolver {
 public:
  std::string name() const override { return "umfpack"; }

 protected:
  bool Analyze(const SpMat& a, std::string* why) override {
    lu_.analyzePattern(a);
    if (lu_.info() != Eigen::Success) {
      *why = "umfpack: symbolic analysis failed";
      return false;
    }
    return true;
  }
  bool NumericFactorize(const SpMat& a, std::string* why) override {
    lu_.factorize(a);
    if (lu_.info() != Eigen::Success) {
      const int code = lu_.umfpackFactorizeReturncode();
      *why = code == UMFPACK_WARNING_singular_matrix
                 ? std::string("umfpack: matrix is singular")
                 : "umfpack: numeric factorisation failed (UMFPACK status " + std::to_string(code) +
                       ")";
      return false;
    }
    return true;
  }
  bool BackSolve(const Vec& b, Vec* x, std::string* why) override {
    *x = lu_.solve(b);
    if (lu_.info() != Eigen::Success) {
      *why = "umfpack: solve failed";
      return false;
    }
    return true;
  }

 private:
  Eigen::UmfPackLU<SpMat> lu_;
};

// KLU (block triangular form + AMD/COLAMD, left-looking; designed for circuit-like matrices).
class KluSolver final : public PatternTrackingSolver {
 public:
  std::string name() const override { return "klu"; }

 protected:
  bool Analyze(const SpMat& a, std::string* why) override {
    klu_.analyzePattern(a);
    if (klu_.info() != Eigen::Success) {
      *why = "klu: symbolic analysis failed (KLU status " +
             std::to_string(klu_.kluCommon().status) + ")";
      return false;
    }
    return true;
  }
  bool NumericFactorize(const SpMat& a, std::string* why) override {
    klu_.factorize(a);
    // KLU reports a singular matrix as a warning (status KLU_SINGULAR > 0) and still returns a
    // factorisation, which Eigen's wrapper then calls a success; the status is the real answer.
    const int status = klu_.kluCommon().status;
    if (klu_.info() != Eigen::Success || status != KLU_OK) {
      *why = status == KLU_SINGULAR
                 ? "klu: matrix is singular (numerical rank " +
                       std::to_string(klu_.kluCommon().numerical_rank) + ")"
                 : "klu: numeric factorisation failed (KLU status " + std::to_string(status) + ")";
      return false;
    }
    return true;
  }
  bool BackSolve(const Vec& b, Vec* x, std::string* why) override {
    *x = klu_.solve(b);
    if (klu_.info() != Eigen::Success) {
      *why = "klu: solve failed";
      return false;
    }
    return true;
  }

 private:
  Eigen::KLU<SpMat> klu_;
};

#endif  // CONTACTBENCH_HAVE_SUITESPARSE

}  // namespace

std::vector<std::string> LinearSolverNames() {
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  return {"sparse-lu", "umfpack", "klu"};
#else
  return {"sparse-lu"};
#endif
}

std::unique_ptr<LinearSolver> MakeLinearSolver(const std::string& name) {
  if (name == "sparse-lu") return std::make_unique<EigenSparseLuSolver>();
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  if (name == "umfpack") return std::make_unique<UmfpackSolver>();
  if (name == "klu") return std::make_unique<KluSolver>();
#endif
  std::string valid;
  for (const std::string& n : LinearSolverNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown linear solver '" + name + "'; valid names: " + valid);
}

}  // namespace cb
