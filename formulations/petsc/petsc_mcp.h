// The step as a bound-constrained mixed complementarity problem (MCP), the form PETSc's SNESVI
// solves: find x with l <= x <= u such that, for every component i,
//   l_i < x_i < u_i  =>  F_i(x) = 0,   x_i = l_i  =>  F_i(x) >= 0,   x_i = u_i  =>  F_i(x) <= 0.
// Written without PETSc's types, so that the tests check it in every build.
//
// Unknowns: the scaled unknowns of the equation formulations, x = (du, g^, r^, dlambda)
// (common/step_equations.h). Bounds and rows, row i paired with unknown i:
//
//   du       free           F1   = (29) / R
//   g^_p     [0, inf)       F2_p = -r^_p + (g^_p + phi_p(u) / L)        = -r^_p + (30)_p / L
//   r^_p     free           F3_p = g^_p + phi_p(u) / L                    = (30)_p / L
//   dlambda  free           F5   = the step constraint (33), fixed load, displacement or (53).
//
// F3 = 0 is (30); where it holds, F2_p = -r^_p, and the pair (g^_p >= 0, -r^_p) is the contact
// condition (11). The gap, not the reaction, carries the bound, and its row adds (30) (zero at
// every solution) so that it depends on g^ itself, as the equilibrium row of a bounded
// displacement does: at a point where the line search has clipped a predicted penetration to
// g^_p = 0, F2_p = -r^_p + phi_p / L > 0 says "closed", and at a closed pair whose reaction has
// turned to tension, F2_p = -r^_p < 0 says "open". Without that term (F2_p = -r^_p, or the bound
// on r^ with the row -g^_p) a reduced-space step that has enforced F2_p = 0 leaves F2_p = 0
// exactly at the clipped point, the active set cannot change, and SNESVINEWTONRSLS stalls
// (observed on P1: line search failure from the cold start at n = 10).
//
// The rows are those of the shared step equations (StepEquationSystem with the complementarity
// row C(a, b) = b = -r^_p), combined per pair by the invertible map (S2, S3) -> (S2 + S3, S2):
// one assembly, one cached pattern, the scaling of the other equation formulations.
//
// A kink step (53): the kink pair's complementarity row is the smooth g^_p + r^_p = 0 of the
// other equation formulations (docs/method.md section 6) and its g^_p is free, so the pair's rows
// are equalities whose only solution with (53) is g_p = r_p = 0.
#pragma once

#include <memory>
#include <vector>

#include "formulations/common/step_equations.h"
#include "formulations/common/step_rows.h"

namespace cb {

// The shared step equations with C(a, b) = b (a = g^_p, b = -r^_p), before the pairs' rows are
// combined (McpRowMap).
class McpStepEquations final : public StepEquationSystem {
 public:
  explicit McpStepEquations(const StepProblem& step, std::shared_ptr<PatternCache> cache = nullptr)
      : StepEquationSystem(step, false, std::move(cache)) {}

 private:
  double Complementarity(double, double b, double) const override { return b; }
  void ComplementarityElement(double, double, double, double* d_a, double* d_b,
                              double* d_rho) const override {
    *d_a = 0.0;
    *d_b = 1.0;
    *d_rho = 0.0;
  }
};

// F of the top of the file at x (the rows of `equations` combined); false where not finite.
bool McpFunction(McpStepEquations& equations, const Vec& x, Vec* f);

// The bounds l, u of the MCP (infinite where an unknown is free): g^_p >= 0 for every pair but
// the kink pair of a kink step.
struct McpBounds {
  Vec lower;
  Vec upper;
};
McpBounds MakeMcpBounds(const StepProblem& step);

// The start in the MCP's unknowns, inside its bounds (SNESVI starts from a feasible point):
//  warm: docs/method.md section 4, (38)-(41) (MakeStepEquationStart), g^0 = max(-phi(u0) / L, 0):
//        (30) and the step constraint hold, except where the predictor penetrates. A pair
//        closed at the known state (r^0 = r^k / R < 0) starts at its bound, g^0 = 0, whatever
//        gap the predictor leaves: RSLS counts a bounded unknown as active only within an
//        absolute 1e-8 of its bound, and a node sliding on a curved obstacle leaves its surface
//        along the linear predictor by a gap of second order in the step (P3: g^0 ~ 4e-8), so
//        the pair would start free, its rows asking for r^ = 0, and the line search crawls
//        (docs/backend-petsc.md). A pair touching at u0 with no reaction yet (g^0 = 0, r^0 = 0:
//        P1's pairs at the zero state) is a tie, and SNESVI counts a bounded unknown with F = 0
//        as free; it starts at r^0 = -kTieReaction instead, so that it starts closed, as the
//        suite's active-set sends ties to the active set (docs/method.md section 8);
//  cold: du0 = 0, dlambda0 fitted to the constraint, the report's g^0 = -1 projected onto the
//        bound, g^0 = 0, and r^0 = -1 (the report's magnitude with a reaction's sign): every pair
//        starts closed (F2_p = 1 + phi_p / L > 0 at its bound), so RSLS's first system is the
//        fully closed one, as the suite's active-set starts; the fully open one is singular for
//        a body held only by its contacts (P1).
Vec MakeMcpStart(const StepProblem& step, const StartPoint& start, const McpBounds& bounds);
// The verdict's tolerance: a reaction no verdict tells from zero.
constexpr double kTieReaction = 1e-8;

// The natural residual of the MCP, ||mid(x - l, F, x - u)||_inf (zero exactly at a solution):
// the history's residual_inf.
double McpNaturalResidual(const Vec& x, const Vec& f, const McpBounds& bounds);

// The MCP's Jacobian in compressed-row form (PETSc's AIJ), made from the step equations'
// column-compressed Jacobian: each stored value is the sum of at most two of its values
// (value[slot] = s[first[slot]] + s[second[slot]], an index -1 adding nothing). Every diagonal
// entry is stored (a structural zero where the rows have none): SNESVINEWTONSSLS adds to the
// diagonal, and the matrix refuses new entries.
struct McpRowMap {
  int size = 0;
  std::vector<int> row_start;  // size + 1 offsets
  std::vector<int> columns;    // ascending within a row
  std::vector<int> first, second;
  std::vector<int> csc_start, csc_rows;  // the step equations' pattern, for SamePattern
};
// `s` is the step equations' Jacobian in each of these.
McpRowMap MakeMcpRowMap(const StepEquationLayout& layout, const SpMat& s);
// Whether `s` has the pattern `map` was made from.
bool SamePattern(const McpRowMap& map, const SpMat& s);
// The MCP Jacobian's values, in the order of map.columns, into values[0 .. nnz).
void FillMcpValues(const McpRowMap& map, const SpMat& s, double* values);
// The MCP Jacobian as a sparse matrix (tests).
SpMat McpJacobian(const McpRowMap& map, const SpMat& s);

// The PETSc formulations' step as rows (common/step_rows.h; petsc_mcp_rows.cc): F of the MCP on
// `local` within the bounds of `step`, from MakeMcpStart, its Jacobian column-compressed.
StepRows McpRows(const StepProblem& step, const StepProblem& local, const StartPoint& start,
                 std::shared_ptr<StepEquationSystem::PatternCache> cache);

}  // namespace cb
