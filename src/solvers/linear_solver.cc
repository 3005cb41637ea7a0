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
#include "solvers/condensed_cholesky.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
#include <klu.h>

#include <Eigen/UmfPackSupport>
#endif

namespace cb {
namespace {

// The part every backend shares: argument checks, the non-finite check, and the decision
// whether the symbolic analysis must be redone, by comparing the pattern with a copy of the
// index arrays last analysed (O(nnz) integer compares, small next to a factorisation).
// A backend whose factorisation keeps referring to the matrix (Eigen's UMFPACK wrapper re-reads
// it in every solve for iterative refinement) asks for a private copy of it, so that a caller
// that refills or destroys its matrix between Factorize and Solve cannot corrupt the solve.
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
      return false;
    }
    return true;
  }

  int num_analyses() const final { return num_analyses_; }
  int num_full_factorizations() const final { return num_full_factorizations_; }
  const std::string& message() const final { return message_; }

 protected:
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
  int num_analyses_ = 0;
  int num_full_factorizations_ = 0;
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
    CountFullFactorization();
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
//
// Two controls differ from UMFPACK's defaults, because the defaults give wrong solutions on our
// Jacobians (relative residual 3 on the first Newton system of `block --set n=100`, 2e-4 at
// n=50; the Newton line search then stagnates). The cause is not Eigen's wrapper or the reuse of
// the symbolic object: the plain C API with default controls does the same on one matrix. It is
//  - the singleton pre-pass: a fixed-load step's constraint row F5 has a single entry, in the
//    dlambda column, so it is a row singleton OFF the diagonal. UMFPACK then cannot use its
//    symmetric strategy (diagonal pivoting on an AMD ordering of A + A^T) and falls back to the
//    unsymmetric one, whatever UMFPACK_STRATEGY says (Info[UMFPACK_STRATEGY_USED] shows it);
//  - the unsymmetric strategy's threshold pivoting (UMFPACK_PIVOT_TOLERANCE 0.1: any pivot at
//    least a tenth of the column's largest entry may be chosen for sparsity). On the stiffness
//    block of a body held only by contact (singular on its own) this compounds along mesh lines
//    to pivot growth of 1e13 (UMFPACK's rcond estimate 3e-17), more than iterative refinement
//    can repair.
// Without the singleton pre-pass the strategy is symmetric again (and the factorisation 2.4x
// faster on that sequence); pivot tolerance 1 (partial pivoting) makes the unsymmetric strategy
// accurate too, for matrices where it is still chosen, and costs nothing under the symmetric
// one. Both were checked on the recorded Newton sequences of block (n = 50, 100) and
// arch-curved: relative residuals <= 3e-13 (block) and 1.2e-10 (arch; as with every backend).
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

// KLU (block triangular form + AMD, left-looking LU with partial pivoting and a preference for
// the diagonal; designed for circuit matrices) through its C API, because Eigen's wrapper
// factorises from scratch every time. Newton refactorises one pattern many times, and
// klu_refactor reuses the pivot order of the last klu_factor: it skips the pivot search and the
// symbolic work of each column (per call 1.7x faster on block n = 50, 1.4x at n = 100, where the
// flops dominate, 4x on arch-curved). The old order can turn bad when the values change a lot
// (in the block's Newton sequence, as contacts settle: pivot growth 1e10 and residuals 5e-8 by
// the 12th iteration, or 1 with KLU's row scaling), so every refactorisation is checked and,
// when suspect, replaced by a full factorisation that pivots afresh. See RefactorIsSound.
//
// Settings, chosen by timing the alternatives on the recorded Newton sequences of block (n = 50
// and 100) and arch-curved (300 steps); 2 cores, noise about 10%:
//  - ordering AMD (the default): COLAMD made 2.4x more fill and was 3.5x slower on the block;
//  - BTF on (the default): a fixed-load step's Jacobian is not irreducible: the constraint row
//    has one entry, in the dlambda column, so it splits off as a 1 x 1 block and the load column
//    stays outside the LU factors. That saved 16% of the flops and ~14% of the time on the
//    block. Arc-length Jacobians are irreducible and pay only the maximum transversal in each
//    analysis. (With row scaling on and BTF off, one arch system was solved only to 1e-6.)
//  - scale -1, NOT the default 2 (rows divided by their largest entry): the formulations already
//    make every row dimensionless (METHOD.md section 2), so KLU's row scaling buys nothing and
//    costs time: without it the block's 13 Newton systems took 0.175 s instead of 0.21 s, n = 100
//    2.0 s instead of 2.1 s, the arch's 601 systems 0.025 s instead of 0.027 s, with relative
//    residuals as good or better (block 3e-12 and 1e-11 instead of 1e-11 and 4e-10; arch 1.3e-10
//    either way). The refactorisation checks below then see unscaled rows, which is again fine
//    for dimensionless rows; like sparse-lu, klu does not equilibrate a badly scaled matrix.
//    -1 rather than 0 also skips KLU's validation pass over the input inside every
//    klu_refactor (7% of a P3 Newton iteration): the input is an Eigen compressed matrix, whose
//    column pointers are monotone and row indices sorted, unique and in range by construction;
//  - tol 0.001 (the default preference for diagonal pivots): 0.01 to 1 changed neither the fill
//    nor the time.
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
    symbolic_ = klu_analyze(static_cast<int>(a.rows()), ColumnPointers(a), RowIndices(a), &common_);
    if (symbolic_ == nullptr) {
      *why = "klu: symbolic analysis failed (KLU status " + std::to_string(common_.status) + ")";
      return false;
    }
    return true;
  }

  bool NumericFactorize(const SpMat& a, std::string* why) override {
    if (numeric_ != nullptr && RefactorIsSound(a)) return true;
    FreeNumeric();
    CountFullFactorization();
    numeric_ = klu_factor(ColumnPointers(a), RowIndices(a), Values(a), symbolic_, &common_);
    // With halt_if_singular (the default) KLU frees the object itself at a zero pivot and
    // reports KLU_SINGULAR; a returned object with a non-OK status is discarded too, so the next
    // call pivots afresh.
    if (numeric_ == nullptr || common_.status != KLU_OK) {
      *why = common_.status == KLU_SINGULAR ? "klu: matrix is singular (zero pivot in column " +
                                                  std::to_string(common_.singular_col) + ")"
                                            : "klu: numeric factorisation failed (KLU status " +
                                                  std::to_string(common_.status) + ")";
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
  // Accept a refactorisation with the previous pivot order only when it is about as accurate as
  // a fresh one. Rejected: a zero pivot; a pivot below machine epsilon times the largest
  // (klu_rcond, min |u_kk| / max |u_kk|: such a pivot is rounding noise). rcond is not invariant
  // to column scaling: for a matrix whose unknowns differ by ~1e16 in scale every
  // refactorisation would be redone in full (correct, just slower). Our unknowns are scaled
  // (METHOD.md section 2).
  //
  // Measured on the block's Newton sequences (n = 50 and 100): fresh factorisations kept
  // rcond >= 9e-9, residuals <= 7e-13. Refactorisations with the first pivot order drift as the
  // contacts settle, rcond falling ~10x per iteration, and the residual follows: 3e-12 at rcond
  // 6e-16 (accepted), 1.4e-10 at 2e-18 and 5e-8 at 4e-27 (both rejected). A pivot-growth test
  // (klu_rgrowth) catches the same cases here but costs a pass over A and U plus a rescaling,
  // measured at 40% of a refactorisation on P3: it is left out. An inexact Newton direction
  // costs at most iterations, never the answer, which the verdict judges.
  static constexpr double kMinRefactorRcond = std::numeric_limits<double>::epsilon();

  bool RefactorIsSound(const SpMat& a) {
    if (klu_refactor(ColumnPointers(a), RowIndices(a), Values(a), symbolic_, numeric_, &common_) ==
            0 ||
        common_.status != KLU_OK) {
      return false;  // a zero pivot in the old order: the values are partly undefined now
    }
    // Negated comparisons so that a NaN estimate also rejects.
    return klu_rcond(symbolic_, numeric_, &common_) != 0 && common_.rcond >= kMinRefactorRcond;
  }

  // KLU's C API takes non-const pointers but only reads the matrix; `a` is the base class's
  // private compressed copy, with int indices like KLU's.
  static_assert(std::is_same_v<SpMat::StorageIndex, int>, "KLU's int API needs int indices");
  static int* ColumnPointers(const SpMat& a) { return const_cast<int*>(a.outerIndexPtr()); }
  static int* RowIndices(const SpMat& a) { return const_cast<int*>(a.innerIndexPtr()); }
  static double* Values(const SpMat& a) { return const_cast<double*>(a.valuePtr()); }

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
  // The condensed Cholesky first: the fastest on every problem of the suite (README, figures),
  // exact through refinement, and KLU (its fallback) where a system has no usable structure.
  // KLU next: the fastest LU, with the refactorisation path that suits Newton's fixed pattern.
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
