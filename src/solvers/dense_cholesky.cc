#include "solvers/dense_cholesky.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <utility>

#include "core/abandonable_work.h"
#include "core/finite.h"

// LAPACK's Fortran interface (liblapack, which CHOLMOD links too). The trailing length is the
// hidden length of the character argument that gfortran passes.
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info,
             std::size_t uplo_length);
void dpotrs_(const char* uplo, const int* n, const int* nrhs, const double* a, const int* lda,
             double* b, const int* ldb, int* info, std::size_t uplo_length);
}

namespace cb {
namespace {

// dpotrf's info for the n x n matrix `a` (lower triangle, overwritten by L).
int FactorizeLower(Mat* a) {
  const int n = static_cast<int>(a->rows());
  int info = 0;
  dpotrf_("L", &n, a->data(), &n, &info, 1);
  return info;
}

// What the worker owns: the matrix (moved in, handed back when it finishes) and dpotrf's info.
struct Job {
  Mat a;
  int info = -1;
};

}  // namespace

bool DenseCholesky::Factorize() {
  factorized_ = false;
  interrupted_ = false;
  if (a_.rows() != a_.cols()) {
    throw std::invalid_argument("DenseCholesky: the matrix is not square");
  }
  const int n = static_cast<int>(a_.rows());
  if (n == 0) {
    factorized_ = true;
    return true;
  }
  if (!AllFinite(a_.data(), a_.size())) return false;
  if (n < kInterruptibleDenseMinOrder) {
    factorized_ = FactorizeLower(&a_) == 0;
    return factorized_;
  }
  auto job = std::make_shared<Job>();
  job->a = std::move(a_);
  const WorkEnd end = RunAbandonably(
      kInterruptibleDenseThreadName, [job] { job->info = FactorizeLower(&job->a); }, [] {});
  if (end == WorkEnd::kAbandoned) {
    interrupted_ = true;  // the worker keeps the matrix until it ends
    return false;
  }
  a_ = std::move(job->a);
  if (end == WorkEnd::kInterruptedBeforeStart) {
    interrupted_ = true;
    return false;
  }
  factorized_ = job->info == 0;
  return factorized_;
}

void DenseCholesky::SolveInPlace(double* b, int ld, int cols) const {
  if (!factorized_) throw std::logic_error("DenseCholesky: SolveInPlace before Factorize");
  const int n = static_cast<int>(a_.rows());
  if (n == 0 || cols == 0) return;
  int info = 0;
  dpotrs_("L", &n, &cols, a_.data(), &n, b, &ld, &info, 1);
  if (info != 0) throw std::logic_error("DenseCholesky: dpotrs refused its arguments");
}

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
