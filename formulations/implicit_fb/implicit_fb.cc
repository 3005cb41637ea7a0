#include "formulations/implicit_fb/implicit_fb.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "formulations/common/reduced_step_system.h"

namespace cb {

bool ImplicitFbOptions::IsValid(std::string* why) const {
  return IsValidSmoothing(eta, gamma_tol, rho_min, why) && solver_options.IsValid(why);
}

// --- start points (docs/method.md section 4) ----------------------------------------------------

ImplicitFbStart MakeImplicitFbStart(const StepProblem& step, const StartPoint& start,
                                    const ImplicitFbOptions& options) {
  const StepEquationLayout layout{step.num_dofs(), step.num_pairs(), /*has_rho=*/true};
  ImplicitFbStart out;
  // (38)-(41) warm, or the cold start of section 5.1: shared with the nonsmooth formulations.
  out.x = MakeStepEquationStart(step, start, layout.size());
  const auto g = out.x.segment(layout.g(), layout.nc);
  const auto r = out.x.segment(layout.r(), layout.nc);
  if (options.eta == EtaCase::kNonsmooth) {
    out.x[layout.rho()] = 0.0;
    return out;
  }
  const double m = layout.nc > 0 ? g.dot(r) / layout.nc : 0.0;
  out.gamma = options.eta == EtaCase::kCase1 ? WarmStartGamma(m, options.gamma_tol) : 1.0;
  const EtaEquation eta{options.eta, out.gamma};
  out.rho_star = layout.nc > 0 ? eta.CompatibleRho(m) : 0.0;
  // (42): keep rho away from 0 so that psi starts smooth; when |rho*| > rho_ the start also
  // satisfies (32) exactly.
  out.x[layout.rho()] = std::abs(out.rho_star) > options.rho_min ? out.rho_star : options.rho_min;
  return out;
}

// --- the formulation ---------------------------------------------------------------------------

namespace {

ImplicitFbOptions Validated(ImplicitFbOptions options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("implicit-fb options: " + why);
  return options;
}

}  // namespace

ImplicitFb::ImplicitFb(ImplicitFbOptions options)
    : options_(Validated(std::move(options))),
      solvers_(options_.solver, options_.solver_options),
      cache_(ImplicitFbSystem::MakePatternCache()) {}

ImplicitFb::~ImplicitFb() = default;

std::string ImplicitFb::name() const { return "implicit-fb"; }

std::string ImplicitFb::settings() const {
  std::ostringstream out;
  out << "solver=" << options_.solver << ";eta=" << static_cast<int>(options_.eta)
      << ";linear_solver=" << options_.solver_options.linear_solver;
  if (options_.reduced_newton) out << ";reduced_newton=" << (*options_.reduced_newton ? 1 : 0);
  return out.str();
}

bool ImplicitFb::DoAccepts(const StepProblem& step, std::string* why) const {
  return !options_.reduced_newton.value_or(false) ||
         ReducedStepSystem::Applies(step, "implicit-fb:reduced_newton", why);
}

void ImplicitFb::DoSolve(const StepProblem& step, const StartPoint& start,
                         const SolveControls& controls, StepResult* result) {
  const ImplicitFbStart initial = MakeImplicitFbStart(step, start, options_);
  ImplicitFbSystem system(step, EtaEquation{options_.eta, initial.gamma}, cache_);
  const StepEquationLayout& l = system.layout();
  Vec x = initial.x;

  if (options_.reduced_newton.value_or(false)) {
    RunReducedStepSolver(solvers_.For(start), system, &x, controls, result);
  } else if (!options_.reduced_newton.has_value() &&
             ReducedStepSystem::Applies(step, "implicit-fb:reduced_newton", nullptr)) {
    RunReducedOrFullStepSolver(solvers_.For(start), system, &x, controls,
                               options_.solver_options.residual_tol, result);
  } else {
    RunStepEquationSolver(solvers_.For(start), system, &x, controls, result);
  }
  result->details["gamma"] = std::to_string(initial.gamma);
  result->details["rho0"] = std::to_string(initial.x[l.rho()]);
  result->details["rho"] = std::to_string(x[l.rho()]);
}

// --- registry factory --------------------------------------------------------------------------

std::unique_ptr<Formulation> MakeImplicitFb(const FormulationConfig& config) {
  OptionReader reader("implicit-fb", config.options);
  ImplicitFbOptions options;
  options.eta = static_cast<EtaCase>(config.eta);  // checked by ImplicitFbOptions::IsValid
  options.solver = config.solver;
  options.solver_options = config.solver_options;
  options.gamma_tol = reader.GetReal("gamma_tol", options.gamma_tol);
  options.rho_min = reader.GetReal("rho_min", options.rho_min);
  const bool reduced_given = config.options.count("reduced_newton") != 0;
  const bool reduced = reader.GetBool("reduced_newton", false);  // read either way: a known key
  if (reduced_given) options.reduced_newton = reduced;
  reader.Finish();
  return std::make_unique<ImplicitFb>(options);
}

}  // namespace cb
