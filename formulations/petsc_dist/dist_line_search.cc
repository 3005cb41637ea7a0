#include "formulations/petsc_dist/dist_line_search.h"

#include <algorithm>
#include <cmath>

#include "solvers/solver_common.h"

namespace cb {

PetscErrorCode DistLineSearch::Install(SNES snes) {
  SNESLineSearch line_search = nullptr;
  PetscErrorCode code = SNESGetLineSearch(snes, &line_search);
  if (code == 0) code = SNESLineSearchSetType(line_search, SNESLINESEARCHSHELL);
  if (code == 0) code = SNESLineSearchShellSetUserFunc(line_search, Apply, this);
  return code;
}

void DistLineSearch::Start(const SolverOptions& options) {
  options_ = options;
  reference_.reset();
}

PetscErrorCode DistLineSearch::Apply(SNESLineSearch line_search, void* context) {
  return static_cast<DistLineSearch*>(context)->Search(line_search);
}

// From x along -y (PETSc's Newton direction solves J y = F): trials w = x - a y with the
// Armijo test m(w) <= reference + armijo a (-2 m(x)), as BacktrackingLineSearch does.
PetscErrorCode DistLineSearch::Search(SNESLineSearch line_search) {
  SNES snes = nullptr;
  ::Vec x = nullptr, f = nullptr, y = nullptr, w = nullptr, g = nullptr;
  PetscReal x_norm = 0.0, f_norm = 0.0, y_norm = 0.0, x_inf = 0.0, y_inf = 0.0;
  PetscErrorCode code = SNESLineSearchGetSNES(line_search, &snes);
  if (code == 0) code = SNESLineSearchGetVecs(line_search, &x, &f, &y, &w, &g);
  if (code == 0) code = SNESLineSearchGetNorms(line_search, &x_norm, &f_norm, &y_norm);
  if (code == 0) code = VecNorm(x, NORM_INFINITY, &x_inf);
  if (code == 0) code = VecNorm(y, NORM_INFINITY, &y_inf);
  if (code != 0) return code;
  const double merit = 0.5 * f_norm * f_norm;
  if (!reference_) reference_.emplace(options_.nonmonotone_window, merit);
  const double reference = reference_->Reference(merit);
  const double slope = -2.0 * merit;
  const double too_short = options_.step_tol * (1.0 + x_inf);
  double a = 1.0;
  for (int trial = 1; trial <= options_.max_backtracks && a * y_inf > too_short; ++trial) {
    PetscReal g_norm = 0.0;
    code = VecWAXPY(w, -a, y, x);
    if (code == 0) code = SNESComputeFunction(snes, w, g);
    if (code == 0) code = VecNorm(g, NORM_2, &g_norm);
    if (code != 0) return code;
    if (!std::isfinite(g_norm)) {
      a *= std::min(0.5, options_.backtrack_max);
      continue;
    }
    const double m = 0.5 * g_norm * g_norm;
    if (m <= reference + options_.armijo * a * slope) {
      reference_->Accept(m, a);
      code = VecCopy(w, x);
      if (code == 0) code = VecCopy(g, f);
      if (code == 0) code = VecNorm(x, NORM_2, &x_norm);
      if (code == 0) code = SNESLineSearchSetNorms(line_search, x_norm, g_norm, y_norm);
      if (code == 0) code = SNESLineSearchSetLambda(line_search, a);
      if (code == 0) code = SNESLineSearchSetReason(line_search, SNES_LINESEARCH_SUCCEEDED);
      return code;
    }
    a = internal::NextBacktrackFactor(options_, merit, slope, a, m);
  }
  return SNESLineSearchSetReason(line_search, SNES_LINESEARCH_FAILED_REDUCT);
}

}  // namespace cb
