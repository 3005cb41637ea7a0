// The Cholesky factorisation of a dense symmetric positive definite matrix by LAPACK (dpotrf,
// dpotrs), for the contact block M of contact_block_factor.h, refactorised every Newton
// iteration. LAPACK runs on the process's BLAS (OpenBLAS in the set-up), which factorises the
// block of P1 n = 400 (802 x 802) several times faster than Eigen's own blocked LLT
// (docs/linear-solvers.md).
#pragma once

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include "core/types.h"

namespace cb {

class DenseCholesky {
 public:
  // The matrix to factorise: fill its lower triangle (the upper one is not read), then call
  // Factorize, which overwrites it with the factor.
  Mat& matrix() { return a_; }
  // A = L L^T in place. False when A is not positive definite (or has a non-finite entry).
  bool Factorize();
  // B = A^-1 B for the `rows` x `cols` block at `b` with leading dimension `ld` (rows must be
  // the order of A): a block of a taller column-major matrix is solved where it lies.
  void SolveInPlace(double* b, int ld, int cols) const;

 private:
  Mat a_;
  bool factorized_ = false;
};

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
