// The one verdict (docs/method.md section 7): whether a step's answer solves the ORIGINAL problem
// (9)-(11) plus the step constraint, computed from the model alone. No formulation's own
// stopping test enters here.
#pragma once

#include "step/step_problem.h"

namespace cb {

// The loosest tolerance a verdict may be asked for (docs/method.md section 7). The residuals are
// relative or scaled, so beyond this an answer could be "verified" whose equilibrium error is
// visible at the accuracy of a plot.
constexpr double kMaxVerdictTolerance = 1e-4;

struct Verdict {
  // ||grad pi(u) - lambda f - grad phi(u)^T r||_inf / max(1, ||lambda f||_inf), (9).
  double eq_res = 0.0;
  // ||min(g / L, -r / R)||_inf with g = -phi(u) from the model, (10)-(11) in the scaled
  // variables of docs/method.md section 2 (a gap and a reaction are compared only after scaling).
  double comp_res = 0.0;
  // max(0, -min_p g_p / L, max_p r_p / R): no penetration, no adhesion.
  double feas_res = 0.0;
  // |c| of the step constraint (StepConstraintValue; dimensionless), with g from the model.
  double step_res = 0.0;
  bool verified = false;   // all four <= tolerance (and finite)
  double tolerance = 0.0;  // the tolerance the answer was judged to
};

// Judges `point` as an answer to `step`. `point.g` is not used: gaps are recomputed from u.
Verdict Judge(const StepProblem& step, const StepPoint& point, double tolerance);

// Pair p counts as in contact when g_p / L < -r_p / R, i.e. the min in comp_res picks the gap.
int CountContacts(const StepProblem& step, const Vec& g, const Vec& r);

}  // namespace cb
