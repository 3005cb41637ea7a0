// The distributed Newton's line search: the serial Newton's backtracking (solvers/solver_common.h,
// NextBacktrackFactor) with its stall guard (solvers/nonmonotone_reference.h), as a PETSc shell
// line search of SNESNEWTONLS, so that the dist-* equations globalise as their serial
// counterparts do and take as many iterations. PETSc's own `bt` is monotone: on a cold P1 step
// (n = 60) dist-implicit-fb took 26 iterations with it where implicit-fb takes 13, crawling at
// factors 0.1-0.4 through the stretch where the serial search measures from the window's
// largest merit. The norms are PETSc's (2-norms reduced over every process), so every process
// takes the same decisions.
#pragma once

#include <petscsnes.h>

#include <optional>

#include "solvers/equation_solver.h"
#include "solvers/nonmonotone_reference.h"

namespace cb {

class DistLineSearch {
 public:
  // Makes this `snes`'s line search (SNESLINESEARCHSHELL); this object must outlive it.
  PetscErrorCode Install(SNES snes);
  // Before each solve: the options of the serial solver for its start (SolverOptionsFor).
  void Start(const SolverOptions& options);

 private:
  static PetscErrorCode Apply(SNESLineSearch line_search, void* context);
  PetscErrorCode Search(SNESLineSearch line_search);

  SolverOptions options_;
  std::optional<NonmonotoneReference> reference_;  // made at the solve's first search
};

}  // namespace cb
