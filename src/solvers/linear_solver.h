// Sparse direct solvers for the (non-symmetric) Newton systems J dx = -F. The symbolic analysis
// (ordering) is done on the first factorisation and redone only when the pattern changes, so a
// path of many steps with one pattern analyses it once. "klu" also reuses the pivot order of its
// last full factorisation while that stays numerically sound (see num_full_factorizations).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "solvers/equation_system.h"

namespace cb {

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  // The block structure of the matrices that follow (nullptr: none). A hint that only
  // structure-exploiting solvers ("cholmod") use; the others ignore it.
  virtual void SetStructure(const JacobianStructure* /*structure*/) {}
  // Numerical factorisation of A (square). Returns false when A is singular to working
  // precision (or the factorisation otherwise fails); message() says why.
  virtual bool Factorize(const SpMat& a) = 0;
  // x = A^{-1} b with the last successful factorisation. Returns false on failure.
  virtual bool Solve(const Vec& b, Vec* x) = 0;
  // How many symbolic analyses were done (for tests and benchmarks).
  virtual int num_analyses() const = 0;
  // How many numerical factorisations chose their pivot order afresh, including ones that found
  // the matrix singular (for tests and benchmarks). Every factorisation does for "sparse-lu" and
  // "umfpack"; "klu" does so only after a new analysis or when reusing the previous pivot order
  // would be inaccurate, and otherwise refactorises more cheaply with the old order.
  virtual int num_full_factorizations() const = 0;
  virtual const std::string& message() const = 0;
  // Whether the last failure of Factorize or Solve was the matrix being singular (to working
  // precision). False for every other failure (out of memory, a non-finite entry, a backend
  // error), which message() names: a caller says "singular" only when this says so.
  virtual bool singular() const = 0;
};

// Names accepted by MakeLinearSolver, the default first.
std::vector<std::string> LinearSolverNames();
// The default: "cholmod" (condensed Cholesky, falling back to "klu") when SuiteSparse was
// built, else "sparse-lu".
std::string DefaultLinearSolverName();
// Throws std::invalid_argument listing the valid names for an unknown one.
std::unique_ptr<LinearSolver> MakeLinearSolver(const std::string& name);

}  // namespace cb
