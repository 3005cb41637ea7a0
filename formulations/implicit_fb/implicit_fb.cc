#include "formulations/implicit_fb/implicit_fb.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace cb {

// --- eta equation (32) ---------------------------------------------------------------------

double EtaEquation::Value(double m, double rho) const {
  switch (eta) {
    case EtaCase::kCase1:
      return -gamma * gamma * m - std::expm1(gamma * rho);
    case EtaCase::kCase2:
      return -m - (rho + rho * rho * rho);
    case EtaCase::kCase3:
      return -m - 2.0 * rho * rho;
    case EtaCase::kNonsmooth:
      return rho;
  }
  return 0.0;
}

double EtaEquation::DerivativeMean(double /*rho*/) const {
  switch (eta) {
    case EtaCase::kCase1:
      return -gamma * gamma;
    case EtaCase::kCase2:
    case EtaCase::kCase3:
      return -1.0;
    case EtaCase::kNonsmooth:
      return 0.0;
  }
  return 0.0;
}

double EtaEquation::DerivativeRho(double rho) const {
  switch (eta) {
    case EtaCase::kCase1:
      return -gamma * std::exp(gamma * rho);
    case EtaCase::kCase2:
      return -(1.0 + 3.0 * rho * rho);
    case EtaCase::kCase3:
      return -4.0 * rho;
    case EtaCase::kNonsmooth:
      return 1.0;
  }
  return 0.0;
}

double EtaEquation::CompatibleRho(double m) const {
  switch (eta) {
    case EtaCase::kCase1: {
      // (43) with gamma^2, consistent with (32): exp(gamma rho) = 1 - gamma^2 m.
      const double argument = 1.0 - gamma * gamma * m;
      if (!(argument > 0.0)) return std::numeric_limits<double>::quiet_NaN();
      return std::log1p(-gamma * gamma * m) / gamma;
    }
    case EtaCase::kCase2: {
      // rho^3 + rho - q = 0 has exactly one real root (the left side is increasing): Cardano,
      // polished by Newton steps against cancellation.
      const double q = -m;
      const double s = std::sqrt(0.25 * q * q + 1.0 / 27.0);
      double rho = std::cbrt(0.5 * q + s) + std::cbrt(0.5 * q - s);
      for (int i = 0; i < 3; ++i) rho -= (rho * rho * rho + rho - q) / (3.0 * rho * rho + 1.0);
      return rho;
    }
    case EtaCase::kCase3:
      if (m > 0.0) return std::numeric_limits<double>::quiet_NaN();
      return std::sqrt(-0.5 * m);
    case EtaCase::kNonsmooth:
      return 0.0;
  }
  return 0.0;
}

double WarmStartGamma(double m, double gamma_tol) {
  // (37): g0^T r0 < nc (1 - gamma_), divided by nc.
  if (m < 1.0 - gamma_tol) return 1.0;
  return std::sqrt((1.0 - gamma_tol) / m);
}

bool ImplicitFbOptions::IsValid(std::string* why) const {
  const int e = static_cast<int>(eta);
  if (e < 1 || e > 4) {
    *why = "eta must be 1, 2, 3 or 4";
    return false;
  }
  if (!(gamma_tol > 0.0 && gamma_tol < 1.0)) {
    *why = "gamma_tol must be in (0, 1)";
    return false;
  }
  if (!(rho_min > 0.0) || !std::isfinite(rho_min)) {
    *why = "rho_min must be positive";
    return false;
  }
  return solver_options.IsValid(why);
}

// --- start points (METHOD.md section 4) ----------------------------------------------------

ImplicitFbStart MakeImplicitFbStart(const StepProblem& step, const StartPoint& start,
                                    const ImplicitFbOptions& options) {
  const ImplicitFbLayout layout{step.num_dofs(), step.num_pairs()};
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

// --- the system ------------------------------------------------------------------------------

ImplicitFbSystem::ImplicitFbSystem(const StepProblem& step, EtaEquation eta,
                                   std::shared_ptr<PatternCache> cache)
    : StepEquationSystem(step, /*has_rho=*/true, std::move(cache)),
      eta_(eta),
      layout_{step.num_dofs(), step.num_pairs()} {
  if (layout_.nc == 0 && eta_.eta != EtaCase::kNonsmooth) {
    // With no contact pairs (32) has no complementarity term; rho = 0 is its only sensible
    // value, which the nonsmooth row F4 = rho states.
    eta_.eta = EtaCase::kNonsmooth;
  }
}

ImplicitFbSystem::~ImplicitFbSystem() = default;

double ImplicitFbSystem::Complementarity(double a, double b, double rho) const {
  return SmoothedFischerBurmeister(a, b, rho);  // (31)
}

void ImplicitFbSystem::ComplementarityElement(double a, double b, double rho, double* d_a,
                                              double* d_b, double* d_rho) const {
  // d/da = a/s - 1, d/db = b/s - 1, d/drho = 2 rho / s; at s = 0 (only with rho = 0 at
  // a = b = 0) the element of the nonsmooth FB function (FischerBurmeisterElement).
  FischerBurmeisterElement(a, b, rho, d_a, d_b, d_rho);
}

double ImplicitFbSystem::ExtraRow(const Vec& x) const {
  const ImplicitFbLayout& l = layout_;
  const double m = l.nc > 0 ? x.segment(l.g(), l.nc).dot(x.segment(l.r(), l.nc)) / l.nc : 0.0;
  return eta_.Value(m, x[l.rho()]);  // (32) / nc
}

void ImplicitFbSystem::AppendExtraRowEntries(std::vector<ScatterPattern::Entry>* e) const {
  const ImplicitFbLayout& l = layout_;
  const int row4 = l.d + 2 * l.nc;
  for (int p = 0; p < l.nc; ++p) {
    e->emplace_back(row4, l.g() + p);
    e->emplace_back(row4, l.r() + p);
  }
  e->emplace_back(row4, l.rho());
}

void ImplicitFbSystem::FillExtraRow(const Vec& x, Cursor* cursor) const {
  const ImplicitFbLayout& l = layout_;
  const double rho = x[l.rho()];
  const double dm = l.nc > 0 ? eta_.DerivativeMean(rho) / l.nc : 0.0;
  for (int p = 0; p < l.nc; ++p) {
    cursor->Add(dm * x[l.r() + p]);  // dF4/dg^ = eta'_m r^ / nc
    cursor->Add(dm * x[l.g() + p]);  // dF4/dr^ = eta'_m g^ / nc
  }
  cursor->Add(eta_.DerivativeRho(rho));
}

// --- the formulation ---------------------------------------------------------------------------

ImplicitFb::ImplicitFb(ImplicitFbOptions options)
    : options_(std::move(options)), cache_(ImplicitFbSystem::MakePatternCache()) {
  std::string why;
  if (!options_.IsValid(&why)) throw std::invalid_argument("implicit-fb options: " + why);
  solver_ = MakeEquationSolver(options_.solver, options_.solver_options);
}

ImplicitFb::~ImplicitFb() = default;

std::string ImplicitFb::name() const { return "implicit-fb"; }

std::string ImplicitFb::settings() const {
  std::ostringstream out;
  out << "solver=" << options_.solver << ";eta=" << static_cast<int>(options_.eta)
      << ";linear_solver=" << options_.solver_options.linear_solver;
  return out.str();
}

void ImplicitFb::DoSolve(const StepProblem& step, const StartPoint& start,
                         const SolveControls& controls, StepResult* result) {
  const ImplicitFbStart initial = MakeImplicitFbStart(step, start, options_);
  ImplicitFbSystem system(step, EtaEquation{options_.eta, initial.gamma}, cache_);
  const ImplicitFbLayout& l = system.layout();
  Vec x = initial.x;

  RunStepEquationSolver(*solver_, system, &x, controls, result);
  result->details["gamma"] = std::to_string(initial.gamma);
  result->details["rho0"] = std::to_string(initial.x[l.rho()]);
  result->details["rho"] = std::to_string(x[l.rho()]);
}

}  // namespace cb
