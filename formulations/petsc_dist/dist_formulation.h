// The formulation every dist-* one is: a serial formulation's rows (common/step_rows.h) on this
// process's contact-only step (petsc_dist_adapter.h), solved by one DistributedSteps kept across
// the steps of a path. Each dist-* file (dist_implicit_fb.cc, dist_nonsmooth_fb.cc,
// dist_active_set.cc, dist_petsc_rsls.cc, dist_petsc_ssls.cc) names its serial counterpart's
// rows and its SNES in a DistRecipe; nothing here knows which formulation it runs.
//
// The equations take the serial Newton's line search with the serial solvers' settings for the
// start (SolverOptionsFor; dist_line_search.h). What the serial ones add around their Newton is
// not repeated: nonsmooth-fb's restart from the cold start, implicit-fb's alternative solvers
// (dogleg, quasi-Newton): PETSc's own are chosen with -snes_type.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "formulations/common/config.h"
#include "formulations/common/step_rows.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "step/formulation.h"

namespace cb {

struct DistRecipe {
  std::string name;       // "dist-active-set"
  std::string snes_type;  // "newtonls" for equations; "vinewtonrsls" / "vinewtonssls" (bounded)
  bool has_rho = false;   // the layout's rho unknown (common/step_equations.h)
  // The serial counterpart's rows of `local` from `start` on `step`.
  std::function<StepRows(const StepProblem& step, const StepProblem& local, const StartPoint& start,
                         const ImplicitFbOptions& options,
                         std::shared_ptr<StepEquationSystem::PatternCache> cache)>
      rows;
  // The serial counterpart's own typed options it reads (none: empty).
  std::function<void(OptionReader& reader, ImplicitFbOptions* options)> read_options;
};

// Backend options `petsc_options` (free text), `linear` (direct or amg; the equations only:
// SNESVI solves on reduced rows, which the field split does not know), then the recipe's.
std::unique_ptr<Formulation> MakeDistFormulation(const DistRecipe& recipe,
                                                 const FormulationConfig& config);

}  // namespace cb
