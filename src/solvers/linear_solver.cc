#include "solvers/linear_solver.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/finite.h"
#include "core/sparse.h"
#include "solvers/condensed_cholesky.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
#include <klu.h>

#include <Eigen/UmfPackSupport>

#include "solvers/interruptible_klu.h"
#endif

namespace cb {
namespace {

// "an n x n matrix with nnz nonzeros", for a failure's message.
std::string Size(const SpMat& a) {
  return "a " + std::to_string(a.rows()) + " x " + std::to_string(a.cols()) + " matrix with " +
         std::to_string(a.nonZeros()) + " nonzeros";
}

// The part every backend shares: argument checks, the non-finite check, and the decision
// whether the symbolic analysis must be redone, by comparing the pattern with a copy of the
// index arrays last analysed (O(nnz) integer compares, small next to a factorisation).
// A backend whose factorisation keeps referring to the matrix (Eigen's UMFPACK wrapper re-reads
// it in every solve for iterative refinement) asks for a private copy of it, so that a caller
// that refills or destroys its matrix between Factorize and Solve cannot corrupt the solve.
class PatternTrackingSolver : public LinearSolver {
 public:
  bool Factorize(const SpMat& a) final {
    CheckSquare(a, name());
    factorized_ = false;
    singular_ = false;
    const SpMat& m = Compressed(a, &uncompressed_scratch_);  // the comparison below reads it
    const double* values = m.valuePtr();
    // The vectorised test first; the scan that names the entry runs only when it fails.
    if (!AllFinite(values, m.nonZeros())) {
      for (Eigen::Index k = 0; k < m.nonZeros(); ++k) {
        if (!std::isfinite(values[k])) {
          message_ = name() + ": matrix has a non-finite entry (value " +
                     std::to_string(values[k]) + " at storage position " + std::to_string(k) + ")";
          return false;
        }
      }
    }
    const bool pattern_changed = !analysed_ || !SamePattern(m);
    const SpMat* factor = &m;
    if (KeepsMatrixReference()) {
      matrix_ = m;
      factor = &matrix_;
    }
    if (pattern_changed) {
      analysed_ = false;
      outer_.assign(m.outerIndexPtr(), m.outerIndexPtr() + m.outerSize() + 1);
      inner_.assign(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
      size_ = m.rows();
      ++num_analyses_;
      if (!Analyze(*factor, &message_)) return false;
      analysed_ = true;
    }
    if (!NumericFactorize(*factor, &message_)) return false;
    factorized_ = true;
    message_.clear();
    return true;
  }

  bool Solve(const Vec& b, Vec* x) final {
    if (x == nullptr) throw std::invalid_argument(name() + ": Solve needs an output vector");
    singular_ = false;
    if (!factorized_) {
      message_ = name() + ": Solve called without a successful factorisation";
      return false;
    }
    if (b.size() != size_) {
      throw std::invalid_argument(name() + ": right-hand side has size " +
                                  std::to_string(b.size()) + ", the matrix has " +
                                  std::to_string(size_) + " rows");
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
      singular_ = true;
      return false;
    }
    return true;
  }

  int num_analyses() const final { return num_analyses_; }
  int num_full_factorizations() const final { return num_full_factorizations_; }
  const std::string& message() const final { return message_; }
  bool singular() const final { return singular_; }

 protected:
  // Set by a backend whose failure is a singular matrix (see LinearSolver::singular).
  void MarkSingular() { singular_ = true; }
  // Symbolic analysis (ordering) of the pattern of `a`.
  virtual bool Analyze(const SpMat& a, std::string* why) = 0;
  // Numerical factorisation of `a`, whose pattern was analysed. Calls CountFullFactorization for
  // each factorisation that chooses its pivots afresh.
  virtual bool NumericFactorize(const SpMat& a, std::string* why) = 0;
  virtual bool BackSolve(const Vec& b, Vec* x, std::string* why) = 0;

  void CountFullFactorization() { ++num_full_factorizations_; }
  // True for a backend whose factorisation refers to the matrix after Factorize returns.
  virtual bool KeepsMatrixReference() const { return false; }

 private:
  bool SamePattern(const SpMat& a) const {
    if (a.rows() != size_ || a.cols() != size_ ||
        static_cast<std::size_t>(a.nonZeros()) != inner_.size()) {
      return false;
    }
    return std::equal(outer_.begin(), outer_.end(), a.outerIndexPtr()) &&
           std::equal(inner_.begin(), inner_.end(), a.innerIndexPtr());
  }

  std::vector<int> outer_, inner_;  // the pattern last analysed
  Eigen::Index size_ = 0;
  SpMat matrix_;  // private copy, for backends that keep referring to the matrix
  SpMat uncompressed_scratch_;
  Vec rhs_;
  bool analysed_ = false;
  bool factorized_ = false;
  bool singular_ = false;
  int num_analyses_ = 0;
  int num_full_factorizations_ = 0;
  std::string message_;
};

// Eigen's supernodal SparseLU with a COLAMD column ordering (partial pivoting). It detects only
// exactly zero pivots; a nearly singular matrix shows up as a huge or non-finite solution.
// x = the factorisation's solve of b by one of Eigen's sparse solvers; false, with
// "NAME: solve failed" in *why, when Eigen reports a failure.
template <typename EigenSolver>
bool EigenBackSolve(const EigenSolver& solver, const char* name, const Vec& b, Vec* x,
                    std::string* why) {
  *x = solver.solve(b);
  if (solver.info() != Eigen::Success) {
    *why = std::string(name) + ": solve failed";
    return false;
  }
  return true;
}

class EigenSparseLuSolver final : public PatternTrackingSolver {
 public:
  std::string name() const override { return "sparse-lu"; }

 protected:
  bool Analyze(const SpMat& a, std::string* /*why*/) override {
    lu_.analyzePattern(a);
    return true;
  }
  bool NumericFactorize(const SpMat& a, std::string* why) override {
    CountFullFactorization();
    lu_.factorize(a);
    if (lu_.info() != Eigen::Success) {
      *why = "sparse-lu: factorisation failed (singular matrix): " + lu_.lastErrorMessage();
      if (lu_.info() == Eigen::NumericalIssue) MarkSingular();
      return false;
    }
    return true;
  }
  bool BackSolve(const Vec& b, Vec* x, std::string* why) override {
    return EigenBackSolve(lu_, "sparse-lu", b, x, why);
  }

 private:
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> lu_;
};

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

// UMFPACK (multifrontal LU with its own column ordering, scaling and iterative refinement).
//
// Two controls differ from UMFPACK's defaults, because the defaults give wrong solutions on our
// Jacobians (docs/linear-solvers.md, "umfpack", has the measurements):
//  - no singleton pre-pass: a fixed-load step's constraint row has a single entry, in the
//    dlambda column, a row singleton OFF the diagonal, which forces the unsymmetric strategy
//    whatever UMFPACK_STRATEGY says;
//  - pivot tolerance 1 (partial pivoting): the unsymmetric strategy's threshold pivoting
//    compounds along mesh lines on the stiffness of a body held only by contact (singular on its
//    own), beyond what iterative refinement repairs.
class UmfpackSolver final : public PatternTrackingSolver {
 public:
  UmfpackSolver() {
    lu_.umfpackControl()(UMFPACK_SINGLETONS) = 0;
    lu_.umfpackControl()(UMFPACK_PIVOT_TOLERANCE) = 1.0;
  }
  std::string name() const override { return "umfpack"; }

 protected:
  bool KeepsMatrixReference() const override { return true; }
  bool Analyze(const SpMat& a, std::string* why) override {
    lu_.analyzePattern(a);
    if (lu_.info() != Eigen::Success) {
      *why = "umfpack: symbolic analysis failed";
      return false;
    }
    return true;
  }
  bool NumericFactorize(const SpMat& a, std::string* why) override {
    CountFullFactorization();
    lu_.factorize(a);
    if (lu_.info() != Eigen::Success) {
      const int code = lu_.umfpackFactorizeReturncode();
      if (code == UMFPACK_WARNING_singular_matrix) MarkSingular();
      *why = code == UMFPACK_WARNING_singular_matrix ? std::string("umfpack: matrix is singular")
             : code == UMFPACK_ERROR_out_of_memory
                 ? "umfpack: out of memory factorising " + Size(a)
                 : "umfpack: numeric factorisation failed (UMFPACK status " + std::to_string(code) +
                       ")";
      return false;
    }
    return true;
  }
  bool BackSolve(const Vec& b, Vec* x, std::string* why) override {
    return EigenBackSolve(lu_, "umfpack", b, x, why);
  }

 private:
  Eigen::UmfPackLU<SpMat> lu_;
};

// KLU (block triangular form + AMD, left-looking LU with partial pivoting and a preference for
// the diagonal; designed for circuit matrices) through its C API, because Eigen's wrapper
// factorises from scratch every time. Newton refactorises one pattern many times, and
// klu_refactor reuses the pivot order of the last klu_factor: it skips the pivot search and the
// symbolic work of each column. The old order can turn bad when the values change a lot (as
// contacts settle in the block's Newton sequence), so every refactorisation is checked and,
// when suspect, replaced by a full factorisation that pivots afresh. See RefactorIsSound.
//
// Settings (chosen by timing the alternatives; docs/linear-solvers.md, "klu"):
//  - ordering AMD (the default): COLAMD makes more fill on the block;
//  - BTF on (the default): a fixed-load step's constraint row has one entry, in the dlambda
//    column, so it splits off as a 1 x 1 block and the load column stays outside the LU factors;
//  - scale -1, not the default 2: the formulations already make every row dimensionless
//    (docs/method.md section 2), so KLU's row scaling buys nothing; -1 rather than 0 also skips
//    KLU's validation pass over the input inside every klu_refactor (an Eigen compressed matrix
//    is valid by construction);
//  - tol 0.001 (the default preference for diagonal pivots).
class KluSolver final : public PatternTrackingSolver {
 public:
  KluSolver() {
    klu_defaults(&common_);
    common_.ordering = 0;  // AMD
    common_.btf = 1;
    common_.scale = -1;  // no row scaling, no validation pass: see above
  }
  ~KluSolver() override { FreeFactors(); }
  KluSolver(const KluSolver&) = delete;
  KluSolver& operator=(const KluSolver&) = delete;

  std::string name() const override { return "klu"; }

 protected:
  bool Analyze(const SpMat& a, std::string* why) override {
    FreeFactors();  // the old numeric object belongs to the old symbolic one
    bool interrupted = false;
    symbolic_ = AnalyseInterruptibly(a, &common_, &interrupted);
    if (interrupted) {
      *why = "klu: symbolic analysis of " + Size(a) + " abandoned on an interrupt";
      return false;
    }
    if (symbolic_ == nullptr) {
      *why = "klu: symbolic analysis failed: " + KluStatus(a);
      return false;
    }
    return true;
  }

  bool NumericFactorize(const SpMat& a, std::string* why) override {
    if (numeric_ != nullptr) {
      bool interrupted = false;
      if (RefactorIsSound(a, &interrupted)) return true;
      if (interrupted) {
        *why = "klu: refactorisation of " + Size(a) + " abandoned on an interrupt";
        return false;
      }
    }
    FreeNumeric();
    // An interrupted factorisation took the symbolic object with it (interruptible_klu.h).
    if (symbolic_ == nullptr && !Analyze(a, why)) return false;
    CountFullFactorization();
    bool interrupted = false;
    numeric_ = FactorInterruptibly(a, &symbolic_, &common_, &interrupted);
    if (interrupted) {
      *why = "klu: factorisation of " + Size(a) + " abandoned on an interrupt";
      return false;
    }
    // With halt_if_singular (the default) KLU frees the object itself at a zero pivot and
    // reports KLU_SINGULAR; a returned object with a non-OK status is discarded too, so the next
    // call pivots afresh.
    if (numeric_ == nullptr || common_.status != KLU_OK) {
      if (common_.status == KLU_SINGULAR) MarkSingular();
      *why = common_.status == KLU_SINGULAR ? "klu: matrix is singular (zero pivot in column " +
                                                  std::to_string(common_.singular_col) + ")"
                                            : "klu: numeric factorisation failed: " + KluStatus(a);
      FreeNumeric();
      return false;
    }
    return true;
  }

  bool BackSolve(const Vec& b, Vec* x, std::string* why) override {
    *x = b;  // klu_solve overwrites the right-hand side with the solution
    if (klu_solve(symbolic_, numeric_, static_cast<int>(x->size()), 1, x->data(), &common_) == 0) {
      *why = "klu: solve failed (KLU status " + std::to_string(common_.status) + ")";
      return false;
    }
    return true;
  }

 private:
  // What KLU's status says, in words (klu.h): a failure other than a singular matrix.
  std::string KluStatus(const SpMat& a) const {
    switch (common_.status) {
      case KLU_OUT_OF_MEMORY:
        return "out of memory factorising " + Size(a) + " (KLU status -2)";
      case KLU_TOO_LARGE:
        return "integer overflow: " + Size(a) +
               " is too large for KLU's int indices (KLU status -4)";
      case KLU_INVALID:
        return "invalid input (KLU status -3)";
      default:
        return "KLU status " + std::to_string(common_.status);
    }
  }

  // Accept a refactorisation with the previous pivot order only when it is about as accurate as
  // a fresh one. Rejected: a zero pivot; a pivot below machine epsilon times the largest
  // (klu_rcond, min |u_kk| / max |u_kk|: such a pivot is rounding noise). rcond is not invariant
  // to column scaling: for a matrix whose unknowns differ by ~1e16 in scale every
  // refactorisation would be redone in full (correct, just slower). Our unknowns are scaled
  // (docs/method.md section 2).
  //
  //
  // Refactorisations with the first pivot order drift as the contacts settle, and the residual
  // follows rcond (docs/linear-solvers.md, "klu"). A pivot-growth test (klu_rgrowth) would catch
  // the same cases at a much higher cost per refactorisation, so it is left out: an inexact
  // Newton direction costs at most iterations, never the answer, which the verdict judges.
  static constexpr double kMinRefactorRcond = std::numeric_limits<double>::epsilon();

  bool RefactorIsSound(const SpMat& a, bool* interrupted) {
    // On an interrupt the worker keeps both objects (interruptible_klu.h): analysed again next.
    if (!RefactorInterruptibly(a, &symbolic_, &numeric_, &common_, interrupted) ||
        common_.status != KLU_OK) {
      return false;  // a zero pivot in the old order: the values are partly undefined now
    }
    // Negated comparisons so that a NaN estimate also rejects.
    return klu_rcond(symbolic_, numeric_, &common_) != 0 && common_.rcond >= kMinRefactorRcond;
  }

  // KLU is called through interruptible_klu.h on the base class's private compressed copy, with
  // int indices like KLU's.
  static_assert(std::is_same_v<SpMat::StorageIndex, int>, "KLU's int API needs int indices");

  void FreeNumeric() {
    if (numeric_ != nullptr) klu_free_numeric(&numeric_, &common_);
  }
  void FreeFactors() {
    FreeNumeric();
    if (symbolic_ != nullptr) klu_free_symbolic(&symbolic_, &common_);
  }

  klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
};

#endif  // CONTACTBENCH_HAVE_SUITESPARSE

}  // namespace

std::vector<std::string> LinearSolverNames() {
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  // The condensed Cholesky first: the fastest on every problem of the suite
  // (docs/linear-solvers.md), exact through refinement, and KLU (its fallback) where a system has
  // no usable structure. KLU next: the fastest LU, with the refactorisation path that suits
  // Newton's fixed pattern.
  return {"cholmod", "klu", "sparse-lu", "umfpack"};
#else
  return {"sparse-lu"};
#endif
}

std::unique_ptr<LinearSolver> MakeLinearSolver(const std::string& name) {
  if (name == "sparse-lu") return std::make_unique<EigenSparseLuSolver>();
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  if (name == "umfpack") return std::make_unique<UmfpackSolver>();
  if (name == "klu") return std::make_unique<KluSolver>();
  if (name == "cholmod") return MakeCondensedCholeskySolver(std::make_unique<KluSolver>());
#endif
  std::string valid;
  for (const std::string& n : LinearSolverNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown linear solver '" + name + "'; valid names: " + valid);
}

std::string DefaultLinearSolverName() { return LinearSolverNames().front(); }

}  // namespace cb
