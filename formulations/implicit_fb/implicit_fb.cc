#include "formulations/implicit_fb/implicit_fb.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/timer.h"

namespace cb {

double SmoothedFischerBurmeister(double a, double b, double rho) {
  return std::sqrt(a * a + b * b + 2.0 * rho * rho) - (a + b);
}

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

namespace {

// Makes (du, dlambda) satisfy the step constraint where that is a matter of the increment
// alone: onto the arc-length sphere by scaling, or the prescribed load / displacement.
void FitIncrementToConstraint(const StepProblem& step, Eigen::Ref<Vec> du, double* dlambda) {
  const StepConstraint& c = step.constraint;
  switch (c.kind) {
    case ConstraintKind::kArcLength: {
      const double w = c.lambda_weight;
      const double norm = std::sqrt(du.squaredNorm() + w * w * (*dlambda) * (*dlambda));
      if (norm > 0.0) {
        du *= c.arc_length / norm;
        *dlambda *= c.arc_length / norm;
      } else if (w > 0.0) {
        *dlambda = c.arc_length / w;  // no direction known: a pure load increment
      }
      break;
    }
    case ConstraintKind::kFixedLoad:
      *dlambda = c.target - step.base.lambda;
      break;
    case ConstraintKind::kDisplacement:
      du[c.index] = c.target - step.base.u[c.index];
      break;
    case ConstraintKind::kKink:
      break;  // (53) involves g and r; nothing to fit in the increment
  }
}

}  // namespace

ImplicitFbStart MakeImplicitFbStart(const StepProblem& step, const StartPoint& start,
                                    const ImplicitFbOptions& options) {
  const ContactModel& model = *step.model;
  ImplicitFbLayout layout{model.num_dofs(), model.num_pairs()};
  const double length = step.scales.length;
  const double force = step.scales.force;
  ImplicitFbStart out;
  out.x = Vec::Zero(layout.size());
  Eigen::Ref<Vec> du = out.x.segment(layout.du(), layout.d);
  auto g = out.x.segment(layout.g(), layout.nc);
  auto r = out.x.segment(layout.r(), layout.nc);
  double dlambda = 0.0;

  if (start.kind == StartKind::kWarm) {
    du = start.du;                                 // (38)
    dlambda = start.dlambda;                       // (41)
    FitIncrementToConstraint(step, du, &dlambda);  // (33) holds exactly
    r = start.r / force;                           // (40)
    Vec phi;
    model.Gaps(step.base.u + du, &phi);
    g = -phi / length;  // (39): (30) holds exactly
  } else {
    FitIncrementToConstraint(step, du, &dlambda);  // du0 = 0
    g.setConstant(-1.0);
    r.setConstant(1.0);
  }
  out.x[layout.dlambda()] = dlambda;

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

struct ImplicitFbSystem::PatternCache {
  const ContactModel* model = nullptr;
  ConstraintKind kind = ConstraintKind::kArcLength;
  int index = -1;
  long nnz_stiffness = -1;
  long nnz_curvature = -1;
  long nnz_gap = -1;
  std::vector<int> load_rows;  // rows where f != 0
  ScatterPattern pattern;
  std::size_t first_stiffness = 0, first_curvature = 0, first_gap_t = 0, first_rest = 0;
  std::size_t first_gap = 0;
};

ImplicitFbSystem::ImplicitFbSystem(const StepProblem& step, EtaEquation eta,
                                   std::shared_ptr<PatternCache> cache)
    : step_(step),
      eta_(eta),
      layout_{step.num_dofs(), step.num_pairs()},
      cache_(cache ? std::move(cache) : std::make_shared<PatternCache>()) {
  if (layout_.nc == 0 && eta_.eta != EtaCase::kNonsmooth) {
    // With no contact pairs (32) has no complementarity term; rho = 0 is its only sensible
    // value, which the nonsmooth row F4 = rho states.
    eta_.eta = EtaCase::kNonsmooth;
  }
}

ImplicitFbSystem::~ImplicitFbSystem() = default;

bool ImplicitFbSystem::Residual(const Vec& x, Vec* residual) {
  const ContactModel& model = *step_.model;
  const ImplicitFbLayout& l = layout_;
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const auto du = x.segment(l.du(), l.d);
  const auto g = x.segment(l.g(), l.nc);
  const auto r = x.segment(l.r(), l.nc);
  const double dlambda = x[l.dlambda()];
  const double rho = x[l.rho()];
  u_ = step_.base.u + du;
  model.InternalForce(u_, &internal_);
  model.Gaps(u_, &phi_);
  model.GapJacobian(u_, &gap_jacobian_);

  residual->resize(l.size());
  const double lambda = step_.base.lambda + dlambda;
  residual->segment(0, l.d) = (internal_ - lambda * model.load_pattern()) / force -
                              gap_jacobian_.transpose() * r;  // (29) / R
  residual->segment(l.d, l.nc) = g + phi_ / length;           // (30) / L
  for (int p = 0; p < l.nc; ++p) {
    (*residual)[l.d + l.nc + p] = SmoothedFischerBurmeister(g[p], -r[p], rho);  // (31)
  }
  if (step_.constraint.kind == ConstraintKind::kKink) {
    // With (53), g^ = r^, psi_p^ = sqrt(2 (g^2 + rho^2)): a cone whose apex is the kink, where
    // Newton stagnates. On (53) psi_p^ = 0 is equivalent to g^ = r^ = 0, stated smoothly here
    // as g^ + r^ = 0; the solution set is unchanged and the Jacobian stays regular.
    const int p = step_.constraint.index;
    (*residual)[l.d + l.nc + p] = g[p] + r[p];
  }
  const double m = l.nc > 0 ? g.dot(r) / l.nc : 0.0;
  (*residual)[l.d + 2 * l.nc] = eta_.Value(m, rho);  // (32) / nc
  (*residual)[l.d + 2 * l.nc + 1] =
      StepConstraintValue(step_, du, dlambda, length * g, force * r);  // (33) etc.
  return residual->allFinite();
}

void ImplicitFbSystem::Jacobian(const Vec& x, SpMat* jacobian) {
  const ContactModel& model = *step_.model;
  const ImplicitFbLayout& l = layout_;
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const auto du = x.segment(l.du(), l.d);
  const auto g = x.segment(l.g(), l.nc);
  const auto r = x.segment(l.r(), l.nc);
  const double dlambda = x[l.dlambda()];
  const double rho = x[l.rho()];
  u_ = step_.base.u + du;
  model.Stiffness(u_, &stiffness_);
  model.GapJacobian(u_, &gap_jacobian_);
  model.GapCurvature(u_, force * r, &curvature_);

  const int row3 = l.d + l.nc;
  const int row4 = l.d + 2 * l.nc;
  const int row5 = row4 + 1;
  const StepConstraint& c = step_.constraint;
  PatternCache& cache = *cache_;
  if (cache.model != &model || cache.kind != c.kind || cache.index != c.index ||
      cache.nnz_stiffness != stiffness_.nonZeros() ||
      cache.nnz_curvature != curvature_.nonZeros() || cache.nnz_gap != gap_jacobian_.nonZeros()) {
    // Entries in the order the fill below adds them.
    std::vector<ScatterPattern::Entry> e;
    cache.first_stiffness = e.size();
    AppendBlockEntries(stiffness_, 0, 0, false, &e);
    cache.first_curvature = e.size();
    AppendBlockEntries(curvature_, 0, 0, false, &e);
    cache.first_gap_t = e.size();
    AppendBlockEntries(gap_jacobian_, 0, l.r(), true, &e);
    cache.first_gap = e.size();
    AppendBlockEntries(gap_jacobian_, l.d, 0, false, &e);
    cache.first_rest = e.size();
    cache.load_rows.clear();
    const Vec& f = model.load_pattern();
    for (int i = 0; i < l.d; ++i) {
      if (f[i] != 0.0) cache.load_rows.push_back(i);
    }
    for (int i : cache.load_rows) e.emplace_back(i, l.dlambda());
    for (int p = 0; p < l.nc; ++p) e.emplace_back(l.d + p, l.g() + p);
    for (int p = 0; p < l.nc; ++p) {
      e.emplace_back(row3 + p, l.g() + p);
      e.emplace_back(row3 + p, l.r() + p);
      e.emplace_back(row3 + p, l.rho());
    }
    for (int p = 0; p < l.nc; ++p) {
      e.emplace_back(row4, l.g() + p);
      e.emplace_back(row4, l.r() + p);
    }
    e.emplace_back(row4, l.rho());
    switch (c.kind) {
      case ConstraintKind::kArcLength:
        for (int j = 0; j < l.d; ++j) e.emplace_back(row5, j);
        e.emplace_back(row5, l.dlambda());
        break;
      case ConstraintKind::kFixedLoad:
        e.emplace_back(row5, l.dlambda());
        break;
      case ConstraintKind::kDisplacement:
        e.emplace_back(row5, c.index);
        break;
      case ConstraintKind::kKink:
        e.emplace_back(row5, l.g() + c.index);
        e.emplace_back(row5, l.r() + c.index);
        break;
    }
    cache.pattern = ScatterPattern(l.size(), l.size(), e);
    cache.model = &model;
    cache.kind = c.kind;
    cache.index = c.index;
    cache.nnz_stiffness = stiffness_.nonZeros();
    cache.nnz_curvature = curvature_.nonZeros();
    cache.nnz_gap = gap_jacobian_.nonZeros();
  }

  const std::vector<int>& slots = cache.pattern.slots();
  cache.pattern.Reset(jacobian);
  // dF1/ddu = (hess pi - sum_p r_p hess phi_p) / R, dF1/dr^ = -grad phi^T.
  ScatterBlock(stiffness_, 1.0 / force, slots, cache.first_stiffness, jacobian);
  ScatterBlock(curvature_, -1.0 / force, slots, cache.first_curvature, jacobian);
  ScatterBlock(gap_jacobian_, -1.0, slots, cache.first_gap_t, jacobian);
  // dF2/ddu = grad phi / L.
  ScatterBlock(gap_jacobian_, 1.0 / length, slots, cache.first_gap, jacobian);
  double* v = jacobian->valuePtr();
  std::size_t k = cache.first_rest;
  const Vec& f = model.load_pattern();
  for (int i : cache.load_rows) v[slots[k++]] += -f[i] / force;  // dF1/ddlambda
  for (int p = 0; p < l.nc; ++p) v[slots[k++]] += 1.0;           // dF2/dg^
  const int kink_pair = c.kind == ConstraintKind::kKink ? c.index : -1;
  for (int p = 0; p < l.nc; ++p) {
    if (p == kink_pair) {  // the row g^ + r^ of the kink pair (see Residual)
      v[slots[k++]] += 1.0;
      v[slots[k++]] += 1.0;
      ++k;
      continue;
    }
    // psi(a, b, rho) with a = g^, b = -r^: d/da = a/s - 1, d/db = b/s - 1, d/drho = 2 rho / s.
    // At s = 0 (only with rho = 0 at a = b = 0) take the element (a/s, b/s) -> (1/sqrt2,
    // 1/sqrt2) of the generalised Jacobian, as for the nonsmooth FB function.
    const double a = g[p];
    const double b = -r[p];
    const double s = std::sqrt(a * a + b * b + 2.0 * rho * rho);
    const double da = s > 0.0 ? a / s - 1.0 : M_SQRT1_2 - 1.0;
    const double db = s > 0.0 ? b / s - 1.0 : M_SQRT1_2 - 1.0;
    v[slots[k++]] += da;                             // dF3/dg^
    v[slots[k++]] += -db;                            // dF3/dr^ (b = -r^)
    v[slots[k++]] += s > 0.0 ? 2.0 * rho / s : 0.0;  // dF3/drho
  }
  const double dm = l.nc > 0 ? eta_.DerivativeMean(rho) / l.nc : 0.0;
  for (int p = 0; p < l.nc; ++p) {
    v[slots[k++]] += dm * r[p];  // dF4/dg^ = eta'_m r^ / nc
    v[slots[k++]] += dm * g[p];  // dF4/dr^ = eta'_m g^ / nc
  }
  v[slots[k++]] += eta_.DerivativeRho(rho);
  switch (c.kind) {
    case ConstraintKind::kArcLength: {
      const double t2 = c.arc_length * c.arc_length;
      for (int j = 0; j < l.d; ++j) v[slots[k++]] += 2.0 * du[j] / t2;
      v[slots[k++]] += 2.0 * c.lambda_weight * c.lambda_weight * dlambda / t2;
      break;
    }
    case ConstraintKind::kFixedLoad:
      v[slots[k++]] += 1.0;
      break;
    case ConstraintKind::kDisplacement:
      v[slots[k++]] += 1.0 / length;
      break;
    case ConstraintKind::kKink:
      v[slots[k++]] += 1.0;
      v[slots[k++]] += -1.0;
      break;
  }
}

// --- the formulation ---------------------------------------------------------------------------

ImplicitFb::ImplicitFb(ImplicitFbOptions options)
    : options_(std::move(options)), cache_(std::make_shared<ImplicitFbSystem::PatternCache>()) {
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

  Stopwatch clock;
  auto observe = [&](const IterationInfo& info) {
    IterationRecord record;
    record.iteration = info.iteration;
    record.merit = info.merit;
    record.residual_inf = info.residual_inf;
    record.step_length = info.step_length;
    double comp = 0.0;
    for (int p = 0; p < l.nc; ++p) {
      comp = std::max(comp, std::abs(std::min((*info.x)[l.g() + p], -(*info.x)[l.r() + p])));
    }
    record.comp_res = comp;
    result->history.push_back(record);
    if (controls.interrupted && controls.interrupted()) return false;
    if (controls.time_limit_s > 0.0 && clock.Seconds() > controls.time_limit_s) return false;
    return true;
  };
  const SolverSummary summary = solver_->Solve(system, &x, observe);

  result->status = summary.status;
  result->message = summary.message;
  result->counts = {summary.iterations, summary.residual_evals, summary.jacobian_evals,
                    summary.linear_solves};
  result->point.du = x.segment(l.du(), l.d);
  result->point.g = step.scales.length * x.segment(l.g(), l.nc);
  result->point.r = step.scales.force * x.segment(l.r(), l.nc);
  result->point.dlambda = x[l.dlambda()];
  result->details["gamma"] = std::to_string(initial.gamma);
  result->details["rho0"] = std::to_string(initial.x[l.rho()]);
  result->details["rho"] = std::to_string(x[l.rho()]);
  result->details["final_merit"] = std::to_string(summary.final_merit);
}

}  // namespace cb
