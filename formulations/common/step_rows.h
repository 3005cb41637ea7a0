// A formulation's step as rows, for a solver outside the formulation: the distributed backend
// (formulations/petsc_dist) solves the rows of a serial formulation over the processes instead
// of the formulation's own solver. Each serial backend that can be distributed exposes a maker
// of its rows (ImplicitFbRows in implicit_fb.h, NonsmoothRows in nonsmooth.h, McpRows in
// petsc/petsc_mcp.h): its system on `local` (the step, or a process's share of it with the
// step's layout), its start on `step` as the serial formulation makes it, its bounds where the
// step is a complementarity problem over them, and what it adds to the result.
#pragma once

#include <functional>
#include <memory>

#include "core/sparse.h"
#include "formulations/common/step_equations.h"
#include "step/formulation.h"

namespace cb {

struct StepRows {
  std::function<bool(const Vec& x, Vec* f)> residual;  // false where not finite
  std::function<void(const Vec& x, SpMat* jacobian)> jacobian;
  StepEquationLayout layout;
  Vec start;
  Vec lower, upper;  // the unknowns' bounds (infinite where free); empty: none (equations)
  // What the formulation adds to the result at the answer x (details); may be empty.
  std::function<void(const Vec& x, StepResult* result)> finish;
  std::shared_ptr<void> owner;  // what the functions read (the system)

  bool bounded() const { return lower.size() > 0; }
};

// The rows of a step equation system, which they keep alive.
StepRows RowsOfSystem(std::shared_ptr<StepEquationSystem> system, Vec start);

}  // namespace cb
