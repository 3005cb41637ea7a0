// A square system of nonlinear equations F(x) = 0 with a sparse Jacobian: what every
// equation solver in src/solvers consumes.
#pragma once

#include "core/types.h"

namespace cb {

class EquationSystem {
 public:
  virtual ~EquationSystem() = default;
  virtual int size() const = 0;
  // F(x). Returns false when F cannot be evaluated at x (non-finite values): the solvers then
  // treat the trial point as rejected.
  virtual bool Residual(const Vec& x, Vec* residual) = 0;
  // J(x) = dF/dx. The sparsity pattern is the same on every call.
  virtual void Jacobian(const Vec& x, SpMat* jacobian) = 0;
};

}  // namespace cb
