// A step as data, for a method written outside the suite (a Python callable or a C++ plug-in,
// docs/your-own-method.md): the step's smooth equations F(x) = 0, their Jacobian, the
// complementarity pairs with their bounds, the scales and the suite's starts. Nothing here is
// new mathematics: the rows are the shared step equations (common/step_equations.h) with the
// complementarity rows left to the method, as the MCP of petsc_mcp.h writes them.
//
// Unknowns x = (du, g^, r^, dlambda), size n = d + 2 nc + 1, g^ = g / L, r^ = r / R (scaled).
// Rows of F (size n - m, m the number of complementarity pairs):
//   F1 = (grad pi(u) - lambda f) / R - grad phi(u)^T r^       (29) / R,     d rows
//   F2 = g^ + phi(u) / L                                        (30) / L,    nc rows
//  [F3 = g^_p + r^_p for the kink pair of a kink step            (53)'s pair, 1 row, else none]
//   F5 = the step constraint c (StepConstraintValue)             (33) etc.,  1 row.
// Complementarity pairs p (every pair but a kink step's): a_p = g^_p >= 0, b_p = -r^_p >= 0,
// a_p b_p = 0, (10)-(11) scaled. F and the pairs together are square: n - m rows + m pairs.
#pragma once

#include <vector>

#include "formulations/common/step_equations.h"
#include "formulations/petsc/petsc_mcp.h"

namespace cb {

class ExternalStepSystem {
 public:
  // `step` must outlive the system.
  explicit ExternalStepSystem(const StepProblem& step);

  const StepProblem& step() const { return step_; }
  const StepEquationLayout& layout() const { return equations_.layout(); }
  int size() const { return layout().size(); }
  int rows() const { return static_cast<int>(rows_.size()); }
  // F(x) into *f (resized to rows()); false where a value is not finite.
  bool Residual(const Vec& x, Vec* f);
  // dF/dx at x, rows() x size(), column-compressed.
  SpMat Jacobian(const Vec& x);
  // The unknowns' indices of the pairs: x[pair_gaps[i]] = g^_p, x[pair_reactions[i]] = r^_p.
  const std::vector<int>& pair_gaps() const { return pair_gaps_; }
  const std::vector<int>& pair_reactions() const { return pair_reactions_; }
  // Bounds of x (infinite where free): g^_p >= 0 and r^_p <= 0 on the pairs.
  const Vec& lower() const { return lower_; }
  const Vec& upper() const { return upper_; }
  // The suite's start of docs/method.md section 4 (MakeStepEquationStart): what nonsmooth-fb
  // and active-set start from.
  Vec Start(const StartPoint& start) const;
  // x in physical units: du, g = L g^, r = R r^, dlambda.
  StepPoint ToPoint(const Vec& x) const;
  // And back: the scaled unknowns of a point.
  Vec FromPoint(const StepPoint& point) const;

 private:
  const StepProblem& step_;
  McpStepEquations equations_;  // the rows with C(a, b) = b on every pair (petsc_mcp.h)
  std::vector<int> rows_;       // the rows of `equations_` that F keeps
  std::vector<int> pair_gaps_, pair_reactions_;
  Vec lower_, upper_;
  Vec all_rows_;  // work storage
};

}  // namespace cb
