// The options of the NLopt formulations (FormulationConfig::options, KEY=VALUE; unknown keys are
// refused), read and checked alike whether or not NLopt was found, so that a bad option is
// reported as such in every build.
#pragma once

#include <string>

#include "formulations/common/config.h"
#include "formulations/implicit_fb/eta_equation.h"

namespace cb {

// nlopt-merit (nlopt_merit.cc): quasi-Newton on m(x) = 1/2 ||F(x)||^2 of (29)-(33).
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

// nlopt-energy (nlopt_energy.cc): fixed-load steps of models with an energy,
// min pi(u) - lambda f^T u s.t. phi(u) <= 0.
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
  // about 8 n^2 + 3 m n doubles, and each iteration takes O(n^3) time): refuse (Accepts) d above
  // this (n = 2000: ~0.26 GB of workspace) rather than run out of memory.
  int max_dense_size = 2000;
  // option `max_gradient_entries`: NLopt's vector-valued constraint takes a DENSE nc x d gradient
  // (nc * d doubles, allocated by NLopt; MMA/CCSAQ keep it for their subproblems): refuse
  // (Accepts) problems above this many entries (default 5e7, 400 MB) rather than run out of
  // memory.
  // P1 n = 50 needs 102 x 5202 = 0.53e6 entries (4 MB); n = 200 needs 402 x 80802 (260 MB).
  double max_gradient_entries = 5e7;

  bool IsValid(std::string* why) const;
};

// nlopt-mpcc (nlopt_mpcc.cc): LD_SLSQP on the step NLP in penalty form.
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
  // option `max_dense_size`: refuse (Accepts) n = d + 2 nc + 1 above this (SLSQP is dense, see
  // above; its constraint Jacobian (d + nc + 1) x n is dense too).
  int max_dense_size = 2000;

  bool IsValid(std::string* why) const;
};

// The options of `config` (config.eta and config.solver_options.residual_tol for nlopt-merit);
// throw std::invalid_argument naming an unknown key or a bad value.
NloptMeritOptions ReadNloptMeritOptions(const FormulationConfig& config);
NloptEnergyOptions ReadNloptEnergyOptions(const FormulationConfig& config);
NloptMpccOptions ReadNloptMpccOptions(const FormulationConfig& config);

}  // namespace cb
