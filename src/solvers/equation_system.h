// A square system of nonlinear equations F(x) = 0 with a sparse Jacobian: what every
// equation solver in src/solvers consumes.
#pragma once

#include "core/types.h"

namespace cb {

// The block structure of a Jacobian, for linear solvers that exploit it (the condensed
// "cholmod" solver, linear_solver.h). Unknowns and rows are ordered
//   x = (v [d], g [nc], r [nc], y [m]),   rows (R1 [d], R2 [nc], R3 [nc], R4 [m]),
// m = size - d - 2 nc, and the Jacobian has the form
//   R1: [ A   0    H    U1 ]     A symmetric, H = -coupling * G^T
//   R2: [ G   E    0    0  ]     E diagonal (non-zero)
//   R3: [ 0   Da   Db   U3 ]     Da, Db diagonal
//   R4: [ V   Vg   Vr   W  ]     a few border rows (dense or sparse)
// (the step equations: v = du, (g, r) per contact pair, y = (dlambda[, rho]); R2 = (30),
// R3 = the complementarity rows, R4 = the extra row and the step constraint). A solver must
// not rely on it beyond what it verifies: the condensed solver checks the block pattern and
// judges its answer by the residual of the full system.
struct JacobianStructure {
  int d = 0;
  int nc = 0;
  double coupling = 1.0;
  // A is dense (the reduced system's A_cc + T): a sparse LU of it has no sparsity to exploit,
  // so a condensing solver condenses whatever d (docs/linear-solvers.md, "cholmod").
  bool dense_stiffness = false;
};

class EquationSystem {
 public:
  virtual ~EquationSystem() = default;
  virtual int size() const = 0;
  // F(x). Returns false when F cannot be evaluated at x (non-finite values): the solvers then
  // treat the trial point as rejected.
  virtual bool Residual(const Vec& x, Vec* residual) = 0;
  // J(x) = dF/dx. The sparsity pattern is the same on every call.
  virtual void Jacobian(const Vec& x, SpMat* jacobian) = 0;
  // F(x) and J(x) together, for a solver that will need J wherever it accepts x: systems that
  // share work between the two override it (and shares_residual_and_jacobian). Returns what
  // Residual returns; *jacobian is then J(x) only when that is true. Equal bit for bit to the
  // two calls (the default).
  virtual bool ResidualAndJacobian(const Vec& x, Vec* residual, SpMat* jacobian) {
    if (!Residual(x, residual)) return false;
    Jacobian(x, jacobian);
    return true;
  }
  // True when ResidualAndJacobian costs less than the two calls. Only then does a solver ask for
  // J ahead of knowing it needs it (a trial point may be rejected or meet the test).
  virtual bool shares_residual_and_jacobian() const { return false; }
  // The rounding floor of each row at x: how far from 0 the row can be when evaluated in double
  // precision at a root, from the sizes of the terms it sums. The solvers consult it only where
  // they cannot go on (the line search stagnates or fails, or the iterations run out): a point
  // whose every |F_i| is within max(residual_tol, floor_i) is then converged, not stuck. False
  // (the default) when the system does not know its terms.
  virtual bool ResidualFloor(const Vec& /*x*/, Vec* /*floor*/) { return false; }
  // The block structure of J (see JacobianStructure), or nullptr when it has none to offer.
  virtual const JacobianStructure* structure() const { return nullptr; }
};

}  // namespace cb
