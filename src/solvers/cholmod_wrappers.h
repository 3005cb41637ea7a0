// RAII wrappers of CHOLMOD (SuiteSparse): the library state with the workspace of its solves, a
// factor it owns, a dense result it owns, and views that hand Eigen storage to CHOLMOD without a
// copy. Nothing here knows what the matrices are; the condensed solver (condensed_system.h)
// builds on it, as Ceres keeps its suitesparse.* apart from the solvers that use them.
#pragma once

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <cholmod.h>

#include <utility>

#include "core/types.h"

namespace cb {

// A cholmod_factor, freed with the cholmod_common that made it (which must outlive it).
class CholmodFactor {
 public:
  CholmodFactor() = default;
  CholmodFactor(cholmod_factor* factor, cholmod_common* common)
      : factor_(factor), common_(common) {}
  ~CholmodFactor() { reset(); }
  CholmodFactor(CholmodFactor&& other) noexcept;
  CholmodFactor& operator=(CholmodFactor&& other) noexcept;
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  void reset();
  // Gives up the factor without freeing it (its new owner frees it).
  cholmod_factor* release() { return std::exchange(factor_, nullptr); }
  cholmod_factor* get() const { return factor_; }
  cholmod_factor* operator->() const { return factor_; }
  explicit operator bool() const { return factor_ != nullptr; }

 private:
  cholmod_factor* factor_ = nullptr;
  cholmod_common* common_ = nullptr;
};

// A dense matrix CHOLMOD allocates as the result of a solve and reuses while its size fits.
class CholmodDense {
 public:
  explicit CholmodDense(cholmod_common* common) : common_(common) {}
  ~CholmodDense();
  CholmodDense(const CholmodDense&) = delete;
  CholmodDense& operator=(const CholmodDense&) = delete;

  // Column-major values, column j starting at data() + j * leading_dimension().
  double* data() const { return static_cast<double*>(dense_->x); }
  std::ptrdiff_t leading_dimension() const { return static_cast<std::ptrdiff_t>(dense_->d); }
  // Where cholmod_solve2 puts (or reallocates) the result.
  cholmod_dense** handle() { return &dense_; }

 private:
  cholmod_dense* dense_ = nullptr;
  cholmod_common* common_;
};

// The CHOLMOD library state, quiet (no printing, no error handler: a failure is a return value),
// and the workspace of cholmod_solve2, kept between solves.
class Cholmod {
 public:
  Cholmod();
  ~Cholmod();
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;

  cholmod_common* common() { return &common_; }

  // The symbolic analysis of `a` with CHOLMOD's own choice of ordering; empty on failure.
  CholmodFactor Analyse(cholmod_sparse* a);
  // The symbolic analysis of `a` in exactly the order `permutation`: supernodal (so that blocks
  // of L can be read off the supernodes) and not postordered (which could move rows); empty on
  // failure.
  CholmodFactor AnalyseInOrder(cholmod_sparse* a, int* permutation);
  // The numerical factorisation of `a` into `factor` (analysed with a's pattern); false unless
  // it completed, i.e. unless `a` is positive definite to working precision.
  bool Factorize(cholmod_sparse* a, const CholmodFactor& factor);
  // One phase `system` (CHOLMOD_A, _P, _L, _Lt, _Pt, ...) of a solve with `factor`, applied to
  // the rows x cols column-major block at `in`, which CHOLMOD reads in place.
  bool SolvePhase(int system, const CholmodFactor& factor, const double* in, int rows, int cols,
                  CholmodDense* out);

 private:
  cholmod_common common_;
  cholmod_dense* solve_workspace_y_ = nullptr;
  cholmod_dense* solve_workspace_e_ = nullptr;
};

// CHOLMOD's view of a symmetric matrix of which `m` (compressed) stores the lower triangle.
cholmod_sparse LowerTriangleView(SpMat& m);

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
