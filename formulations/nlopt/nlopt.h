// NLopt renderings of a step (issue 3): `nlopt-merit` (1/2 ||F||^2 of the implicit smoothed-FB
// system), `nlopt-energy` (fixed-load energy NLP) and `nlopt-mpcc` (penalty-form step NLP).
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
//    STOPVAL/FTOL/XTOL_REACHED -> kConverged; MAXEVAL/MAXTIME_REACHED -> kLimitReached;
//    a stop forced because SolveControls::interrupted() said so -> kStoppedByCaller, because of
//    the time limit -> kLimitReached (whatever code NLopt returns then); a non-finite
//    objective, constraint or gradient from the model -> kFailed (forced stop; the message
//    names what and at which evaluation); every failure
//    (ROUNDOFF_LIMITED included) -> kFailed, but the point NLopt returned is kept: the verdict
//    decides.
//  - SolveControls are polled in every callback; interrupted() or the time limit force a stop
//    (nlopt_force_stop; the time limit is also NLopt's maxtime). An exception thrown inside a
//    callback (by the model, say) is caught there, NLopt is force-stopped, and the exception is
//    rethrown after nlopt_optimize returns: nothing crosses NLopt's C frames (ARCHITECTURE.md habit
//    2).
//  - Options travel as FormulationConfig::options (KEY=VALUE); unknown keys are refused.
#pragma once

#include <memory>
#include <string>

#include "formulations/config.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has NLopt (CONTACTBENCH_HAVE_NLOPT).
bool NloptAvailable();
std::unique_ptr<Formulation> MakeNloptMerit(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig& config);

// nlopt-merit: quasi-Newton on m(x) = 1/2 ||F(x)||^2 of (29)-(33) (the approach of the report's
// truss examples, through NLopt). Start: MakeImplicitFbStart (warm (38)-(43) or cold).
// Findings (measured): it meets the verdict at 1e-8 on the bar (22 evaluations) and on the
// first 20 steps of the two-bar truss onto a floor, but near the contact kink of that path
// LBFGS stops ("SUCCESS", gradient test) at stationary points of the merit with ||F|| ~ 1e-3
// (J^T F = 0 with F != 0), and on P1 (J^T J with the square of an ill-conditioned stiffness's
// condition number) it makes no progress: slower than Newton on the same system, and less
// reliable - a finding about the approach, not a defect of the rendering.
struct NloptMeritOptions {
  std::string algorithm = "lbfgs";  // option `algorithm`: lbfgs (LD_LBFGS) | tnewton (LD_TNEWTON)
  EtaCase eta = EtaCase::kCase1;    // FormulationConfig::eta
  double gamma_tol = 1e-2;          // option `gamma_tol`: gamma_ of (37)
  double rho_min = 1e-3;            // option `rho_min`: rho_ of (42)
  // option `residual_tol`: stop (NLopt's stopval) once s/2 ||F||^2 <= s/2 residual_tol^2, which
  // implies ||F||_inf <= residual_tol: the same test as the Newton solvers' (SolverOptions).
  // Default: FormulationConfig::solver_options.residual_tol (1e-10).
  double residual_tol = 1e-10;
  // option `merit_scale`: s. NLopt's LBFGS (Luksan's code) also stops, as "success", when
  // max_i |grad_i| <= 1e-8, a hard-wired ABSOLUTE test. With grad = J^T F and ||J|| ~ 1e2 that
  // fires around ||F|| ~ 1e-10, at the edge of what the verdict's 1e-8 needs. NLopt therefore
  // minimises M(y) = s m(y / sqrt(s)) (NloptMeritObjective): the same iterates, first step
  // included (scaling the merit alone would not do: the first LBFGS step is -grad, and it would
  // be s times too long), while the test becomes ||J^T F||_inf <= 1e-8 / sqrt(s) = 1e-12.
  double merit_scale = 1e8;
  // option `ftol_rel` / `xtol_rel`: NLopt's relative tests; 0 leaves Luksan's own floors
  // (1e-14 on f changes, 1e-16 on x changes, i.e. stagnation only).
  double ftol_rel = 0.0;
  double xtol_rel = 0.0;
  int maxeval = 20000;  // option `maxeval`: objective evaluations
  int memory = 0;       // option `memory`: LBFGS/TNEWTON stored updates (0: NLopt's default)

  bool IsValid(std::string* why) const;
};

// nlopt-energy: fixed-load steps of models with an energy: min pi(u) - lambda f^T u s.t.
// phi(u) <= 0 (NloptEnergyProblem for the scaling). A floor every energy method meets: near the
// optimum a step that reduces the residual e of (29) lowers the energy by only ~ e^2 / K, which
// vanishes below the energy's rounding (eps |pi|) long before e meets the verdict; measured,
// MMA and CCSAQ stall at eq_res 4e-8 / 9e-8 on a 2-unknown LCP (SLSQP, whose QP step is exact
// on a quadratic, reaches 0), and SLSQP stalls at 1.4e-6 on P1 n = 10, where MMA and CCSAQ,
// first-order on that ill-conditioned energy, are still at 1e-3 after 20000 evaluations. Start: du0
// = start.du (warm; the path driver's fixed-load start is du = 0) or du0 = 0 (cold). Reactions by
// least squares from (29) on the active pairs (NloptEnergyProblem::Recover).
struct NloptEnergyOptions {
  std::string algorithm = "mma";  // option `algorithm`: mma (LD_MMA) | ccsaq (LD_CCSAQ) | slsqp
  // option `ftol_rel`: 0 (off) by default. Near the optimum the energy changes by ~ (gradient)^2
  // / stiffness, below its rounding long before the gradient meets the verdict (a relative
  // change of 1e-15 stopped LCP fixtures at eq_res 4e-8): x changes decide instead.
  double ftol_rel = 0.0;
  double xtol_rel = 1e-13;  // option `xtol_rel` (on y = du / L)
  // option `constraint_tol`: NLopt's feasibility tolerance on phi/L (which points count as
  // feasible when NLopt picks the best one); the verdict's feas_res is on g/L.
  double constraint_tol = 1e-10;
  int maxeval = 20000;       // option `maxeval`: objective evaluations
  double active_tol = 1e-6;  // option `active_tol`: pairs with g/L <= this carry reactions
  // option `max_dense_size`: SLSQP is dense (its workspace, length_work in NLopt's slsqp.c, is
  // about 8 n^2 + 3 m n doubles, and each iteration takes O(n^3) time): refuse d above this
  // (n = 2000: ~0.26 GB of workspace) with std::invalid_argument rather than run out of memory.
  int max_dense_size = 2000;
  // option `max_gradient_entries`: NLopt's vector-valued constraint takes a DENSE nc x d gradient
  // (nc * d doubles, allocated by NLopt; MMA/CCSAQ keep it for their subproblems): refuse
  // problems above this many entries (default 5e7, 400 MB) rather than run out of memory.
  // P1 n = 50 needs 102 x 5202 = 0.53e6 entries (4 MB); n = 200 needs 402 x 80802 (260 MB).
  double max_gradient_entries = 5e7;

  bool IsValid(std::string* why) const;
};

// nlopt-mpcc: LD_SLSQP on the step NLP in penalty form (NloptMpccProblem). Start: warm, the
// implicit formulation's warm start (38)-(41) with g^, r^ moved bound_push inside the bounds;
// cold,
// du0 = 0, dlambda0 fitted to the step constraint, g^ = 1, r^ = -1 (the report's cold
// magnitudes with the signs the bounds demand).
struct NloptMpccOptions {
  double weight = 1.0;  // option `weight`: w of the penalty w sum_p (-g^_p r^_p)
  // option `residual_tol`: NLopt's tolerance on each equality row (which points count as
  // feasible); stopval = w residual_tol^2 on the penalty (then every min(g^, -r^) <= tol).
  double residual_tol = 1e-10;
  // option `ftol_rel`: 0 (off) by default: the penalty is exactly 0 at consecutive iterates on
  // the bounds while the equality rows are still converging, which NLopt's relative test
  // takes for convergence.
  double ftol_rel = 0.0;
  double xtol_rel = 1e-13;  // option `xtol_rel`
  int maxeval = 5000;       // option `maxeval`
  // option `bound_push`: the warm start's g^, r^ are moved to at least this far inside their
  // bounds (g^ >= bound_push, r^ <= -bound_push), off the degenerate corner g^ = r^ = 0.
  double bound_push = 1e-2;
  // option `max_dense_size`: refuse n = d + 2 nc + 1 above this (SLSQP is dense, see above;
  // its constraint Jacobian (d + nc + 1) x n is dense too).
  int max_dense_size = 2000;

  bool IsValid(std::string* why) const;
};

}  // namespace cb
