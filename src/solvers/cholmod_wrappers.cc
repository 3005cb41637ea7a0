#include "solvers/cholmod_wrappers.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <utility>

namespace cb {

CholmodFactor::CholmodFactor(CholmodFactor&& other) noexcept
    : factor_(std::exchange(other.factor_, nullptr)), common_(other.common_) {}

CholmodFactor& CholmodFactor::operator=(CholmodFactor&& other) noexcept {
  if (this != &other) {
    reset();
    factor_ = std::exchange(other.factor_, nullptr);
    common_ = other.common_;
  }
  return *this;
}

void CholmodFactor::reset() {
  if (factor_ != nullptr) cholmod_free_factor(&factor_, common_);
}

CholmodDense::~CholmodDense() { cholmod_free_dense(&dense_, common_); }

Cholmod::Cholmod() {
  cholmod_start(&common_);
  common_.print = 0;
  common_.error_handler = nullptr;
}

Cholmod::~Cholmod() {
  cholmod_free_dense(&solve_workspace_y_, &common_);
  cholmod_free_dense(&solve_workspace_e_, &common_);
  cholmod_finish(&common_);
}

CholmodFactor Cholmod::Analyse(cholmod_sparse* a) {
  return CholmodFactor(cholmod_analyze(a, &common_), &common_);
}

CholmodFactor Cholmod::AnalyseInOrder(cholmod_sparse* a, int* permutation) {
  const int nmethods = common_.nmethods, ordering = common_.method[0].ordering;
  const int postorder = common_.postorder, supernodal = common_.supernodal;
  common_.nmethods = 1;
  common_.method[0].ordering = CHOLMOD_GIVEN;
  common_.postorder = 0;
  common_.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_factor* factor = cholmod_analyze_p(a, permutation, nullptr, 0, &common_);
  common_.nmethods = nmethods;
  common_.method[0].ordering = ordering;
  common_.postorder = postorder;
  common_.supernodal = supernodal;
  return CholmodFactor(factor, &common_);
}

bool Cholmod::Factorize(cholmod_sparse* a, const CholmodFactor& factor) {
  return cholmod_factorize(a, factor.get(), &common_) && common_.status == CHOLMOD_OK &&
         factor->minor == factor->n;
}

bool Cholmod::SolvePhase(int system, const CholmodFactor& factor, const double* in, int rows,
                         int cols, CholmodDense* out) {
  cholmod_dense rhs{};
  rhs.nrow = static_cast<std::size_t>(rows);
  rhs.ncol = static_cast<std::size_t>(cols);
  rhs.nzmax = rhs.nrow * rhs.ncol;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(in);
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  return cholmod_solve2(system, factor.get(), &rhs, nullptr, out->handle(), nullptr,
                        &solve_workspace_y_, &solve_workspace_e_, &common_) != 0;
}

cholmod_sparse LowerTriangleView(SpMat& m) {
  cholmod_sparse s{};
  s.nrow = static_cast<std::size_t>(m.rows());
  s.ncol = static_cast<std::size_t>(m.cols());
  s.nzmax = static_cast<std::size_t>(m.nonZeros());
  s.p = m.outerIndexPtr();
  s.i = m.innerIndexPtr();
  s.x = m.valuePtr();
  s.stype = -1;  // the lower triangle stored
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
