// The error the FCLIB literature reports for an answer (Acary, Bremond & Huber, INRIA RR-9118;
// Siconos' fc3d_compute_error.c and gfc3d_compute_error.c): the natural-map residual relative
// to the problem's data, so that the suite's figures can be set beside published ones. It is
// not the verdict (verdict.h decides whether a step is solved); it is a second figure, in the
// community's own measure, of the same answer. docs/problem-files.md, "The FCLIB error".
//
// With mu = 0 the natural map r - proj_K(r - u) of a contact reduces to min(r_N, u_N) (K is
// the half-line r_N >= 0), so:
//
//   local problem (an LCP  u = W z + q):      ||min(z, W z + q)||_2 / ||q||_2
//   global problem (a linear body  K v = f + reactions, u_N = gaps):
//     sqrt(||K^{-1} e(v, r)||_2^2 + ||min(-r, g(v))||_2^2) / (1 + ||lambda f||_2)
//
// e the equilibrium residual of (9), g = -phi the gaps and -r >= 0 the reactions. As in
// Siconos the local error is absolute when ||q|| is below the machine epsilon.
#pragma once

#include "model/contact_model.h"
#include "step/step_problem.h"

namespace cb {

// The FCLIB error of `state` (u, r at load lambda) as an answer of `model`'s fixed-load
// problem at lambda. NaN when the model is not linear (there is no FCLIB problem of it) or K
// cannot be factorised or is singular to working precision (a body held by its contacts
// alone, P1 `block`: K^{-1} e would be rounding amplified).
double NaturalMapError(const ContactModel& model, const State& state);

// The same of `point` as an answer of the fixed-load `step`: of the state base + point.
double NaturalMapError(const StepProblem& step, const StepPoint& point);

}  // namespace cb
