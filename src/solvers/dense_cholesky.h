// The Cholesky factorisation of a dense symmetric positive definite matrix by LAPACK (dpotrf,
// dpotrs), for the contact block M of contact_block_factor.h, refactorised every Newton
// iteration. LAPACK runs on the process's BLAS (OpenBLAS in the set-up), which factorises the
// block of P1 n = 400 (802 x 802) several times faster than Eigen's own blocked LLT
// (docs/linear-solvers.md). On a 3-D body the block is large (hertz-3d at n = 54: c up to
// 9 075, a third of 7.5e11 flops, tens of seconds), so a large one is factorised on a worker
// thread an interrupt abandons (core/abandonable_work.h), which owns the matrix while it works.
#pragma once

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include "core/types.h"

namespace cb {

// Matrices of a smaller order are factorised on the calling thread (1 000: a third of 1e9 flops,
// well under a second).
constexpr int kInterruptibleDenseMinOrder = 1000;

// The worker thread's name (at most 15 characters).
constexpr const char* kInterruptibleDenseThreadName = "dense-factor";

class DenseCholesky {
 public:
  // The matrix to factorise: fill its lower triangle (the upper one is not read), then call
  // Factorize, which overwrites it with the factor.
  Mat& matrix() { return a_; }
  // A = L L^T in place. False when A is not positive definite (or has a non-finite entry), or
  // when an interrupt abandoned the factorisation (then interrupted() and the matrix is empty:
  // the worker took it).
  bool Factorize();
  bool interrupted() const { return interrupted_; }
  // B = A^-1 B for the `rows` x `cols` block at `b` with leading dimension `ld` (rows must be
  // the order of A): a block of a taller column-major matrix is solved where it lies.
  void SolveInPlace(double* b, int ld, int cols) const;

 private:
  Mat a_;
  bool factorized_ = false;
  bool interrupted_ = false;
};

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
