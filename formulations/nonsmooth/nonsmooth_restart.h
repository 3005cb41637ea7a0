// The restart of a warm arc-length solve that stalled far from a solution
// (NonsmoothOptions::restart; "Restart" in nonsmooth.h): whether to take it, and its start.
#pragma once

#include "formulations/common/step_equations.h"
#include "formulations/nonsmooth/nonsmooth.h"
#include "solvers/equation_solver.h"
#include "step/formulation.h"

namespace cb {

// Whether the first run's `summary` calls for the restart: it is enabled, the run stopped of
// itself (not converged, stopped or timed out) above restart_residual, from a warm start, on an
// arc-length step with a load term.
bool TakesRestart(const NonsmoothOptions& options, const SolverSummary& summary,
                  const StepProblem& step, const StartPoint& start);

// The restart's start point: du0 = t du_pred with t the largest fraction of the predictor that
// opens no gap below min(g^k, 0) (bisection), and dlambda0 = -sign(dlambda_pred)
// sqrt(theta^2 - ||du0||^2) / w, so that (33) holds.
StartPoint RestartPoint(const StepProblem& step, const StartPoint& start, int nc);

// In the scaled start x of `again`: the reactions of the pairs closed at du0 (g^ <= 1e-8), the
// least-squares solution of (29), G_c^T r_c = grad pi(u0) - lambda0 f, clipped to r <= 0.
void LeanOnClosedPairs(const StepProblem& step, const StartPoint& again,
                       const StepEquationLayout& l, Vec* x);

}  // namespace cb
