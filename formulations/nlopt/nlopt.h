// The NLopt backend: `nlopt-merit` (1/2 ||F||^2 of the implicit smoothed-FB system,
// nlopt_merit.cc), `nlopt-energy` (fixed-load energy NLP, nlopt_energy.cc) and `nlopt-mpcc`
// (penalty-form step NLP, nlopt_mpcc.cc), on the functions of nlopt_problems.h through the
// adapter of nlopt_adapter.h, with the options of nlopt_options.h. Without NLopt, nlopt_stub.cc
// stands in (nlopt.cmake chooses).
//
// Common to all three (COMPARISON.md "Counting rule"):
//  - NLopt has no iteration counter, so `iterations` counts OBJECTIVE EVALUATIONS (settings()
//    says so with "iterations=evaluations"); residual_evals = objective evaluations plus
//    constraint evaluations; jacobian_evals = evaluations that asked for gradients (objective
//    and constraints); linear_solves = 0. One StepResult::history row per objective evaluation:
//    merit = 1/2 ||F||^2 (nlopt-merit) or the NLP objective (nlopt-energy, nlopt-mpcc);
//    residual_inf = ||F||_inf (merit) or the constraint violation at that point (energy:
//    max phi/L; mpcc: max |equality row|); comp_res = ||min(g/L, -r/R)||_inf (NaN for energy,
//    whose reactions exist only at the end); step_length = ||x - previous evaluated x||_2.
//  - details["nlopt_result"] = "<code> <NAME>" (the raw nlopt_result); Status: SUCCESS,
//    STOPVAL/FTOL/XTOL_REACHED -> kConverged; MAXEVAL_REACHED -> kLimitReached;
//    MAXTIME_REACHED -> kTimeLimit; a stop forced because SolveControls::interrupted() said so ->
//    kStoppedByCaller, because of the time limit -> kTimeLimit (whatever code NLopt returns then);
//    a non-finite objective, constraint or gradient from the model -> kFailed (forced stop; the
//    message names what and at which evaluation); every failure (ROUNDOFF_LIMITED included) ->
//    kFailed, but the point NLopt returned is kept: the verdict decides.
//  - SolveControls are polled in every callback; interrupted() or the time limit force a stop
//    (nlopt_force_stop; the time limit is also NLopt's maxtime). An exception thrown inside a
//    callback (by the model, say) is caught there, NLopt is force-stopped, and the exception is
//    rethrown after nlopt_optimize returns: nothing crosses NLopt's C frames (docs/architecture.md,
//    house rule 2).
//  - Options travel as FormulationConfig::options (KEY=VALUE); unknown keys are refused.
#pragma once

#include <memory>
#include <string>

#include "formulations/common/config.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has NLopt (defined by the adapter, or false by the stub).
bool NloptAvailable();
// The version of NLopt this build is linked with, from its headers or library; "" without it.
std::string NloptVersion();
// Registry factories; without NLopt they read the options, then throw std::invalid_argument.
std::unique_ptr<Formulation> MakeNloptMerit(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig& config);

}  // namespace cb
