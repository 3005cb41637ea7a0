#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "formulations/nonsmooth/nonsmooth.h"

namespace cb {

std::string NonsmoothName(ComplementarityFunction function) {
  return function == ComplementarityFunction::kMin ? "active-set" : "nonsmooth-fb";
}

bool NonsmoothOptions::IsValid(std::string* why) const {
  if (function != ComplementarityFunction::kFischerBurmeister &&
      function != ComplementarityFunction::kMin) {
    *why = "function must be Fischer-Burmeister or min";
    return false;
  }
  if (!(restart_residual >= 0.0)) {
    *why = "restart_residual must be >= 0";
    return false;
  }
  return solver_options.IsValid(why);
}

// --- the formulation -------------------------------------------------------------------------

namespace {

NonsmoothOptions Validated(NonsmoothOptions options) {
  std::string why;
  if (!options.IsValid(&why)) {
    throw std::invalid_argument(NonsmoothName(options.function) + " options: " + why);
  }
  return options;
}

}  // namespace

NonsmoothFormulation::NonsmoothFormulation(NonsmoothOptions options)
    : options_(Validated(std::move(options))),
      solvers_(options_.solver, options_.solver_options),
      cache_(StepEquationSystem::MakePatternCache()) {}

NonsmoothFormulation::~NonsmoothFormulation() = default;

std::string NonsmoothFormulation::name() const { return NonsmoothName(options_.function); }

std::string NonsmoothFormulation::settings() const {
  std::ostringstream out;
  out << "solver=" << options_.solver
      << ";function=" << (options_.function == ComplementarityFunction::kMin ? "min" : "fb")
      << ";linear_solver=" << options_.solver_options.linear_solver;
  return out.str();
}

void NonsmoothFormulation::DoSolve(const StepProblem& step, const StartPoint& start,
                                   const SolveControls& controls, StepResult* result) {
  NonsmoothSystem system(step, options_.function, cache_);
  const StepEquationLayout& l = system.layout();
  Vec x = MakeStepEquationStart(step, start, l.size());

  // Active sets A = {p : g^_p <= -r^_p} met along the iteration: a set seen before, but not at
  // the previous iterate, is a revisit (the cycling PDAS can show without a safeguard).
  auto active_set = [&l](const Vec& y) {
    std::vector<bool> a(l.nc);
    for (int p = 0; p < l.nc; ++p) a[p] = y[l.g() + p] <= -y[l.r() + p];
    return a;
  };
  std::vector<std::vector<bool>> seen = {active_set(x)};
  int changes = 0;
  int revisits = 0;
  auto on_iteration = [&](const Vec& y) {
    std::vector<bool> a = active_set(y);
    if (a == seen.back()) return;
    ++changes;
    for (const auto& s : seen) {
      if (s == a) {
        ++revisits;
        break;
      }
    }
    seen.push_back(std::move(a));
  };
  SolverSummary summary =
      RunStepEquationSolver(solvers_.For(start), system, &x, controls, result, on_iteration);

  const StepConstraint& c = step.constraint;
  const bool restart = options_.restart && summary.status != Status::kConverged &&
                       summary.status != Status::kStoppedByCaller &&
                       summary.status != Status::kTimeLimit &&
                       !(summary.final_residual_inf <= options_.restart_residual) &&
                       start.kind == StartKind::kWarm && c.kind == ConstraintKind::kArcLength &&
                       c.lambda_weight > 0.0;
  result->details["restarted"] = restart ? "1" : "0";
  if (restart) {
    // See "Restart" in the header: back along the predictor to the first contact, then turn.
    StartPoint again = start;
    const Vec& u = step.base.u;
    Vec phi;
    step.model->Gaps(u, &phi);
    const double floor = std::min(l.nc > 0 ? (-phi).minCoeff() : 0.0, 0.0);
    auto opens = [&](double t) {
      step.model->Gaps(u + t * start.du, &phi);
      return l.nc == 0 || (-phi).minCoeff() >= floor;
    };
    double t = 1.0;
    if (!opens(1.0)) {
      double lo = 0.0, hi = 1.0;
      for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (opens(mid) ? lo : hi) = mid;
      }
      t = lo;
    }
    again.du = t * start.du;
    const double rest = c.arc_length * c.arc_length - again.du.squaredNorm();
    again.dlambda =
        (start.dlambda > 0.0 ? -1.0 : 1.0) * std::sqrt(std::max(rest, 0.0)) / c.lambda_weight;
    x = MakeStepEquationStart(step, again, l.size());
    // Reactions of the pairs closed at du0 (g^ <= 1e-8): the least-squares solution of (29),
    // G_c^T r_c = grad pi(u0) - lambda0 f, clipped to r <= 0, so the start leans on the
    // contact it has just met instead of sitting at the degenerate g = r = 0.
    std::vector<int> closed;
    for (int p = 0; p < l.nc; ++p) {
      if (x[l.g() + p] <= 1e-8) closed.push_back(p);
    }
    if (!closed.empty()) {
      const Vec u0 = u + again.du;
      Vec out_of_balance;
      step.model->InternalForce(u0, &out_of_balance);
      out_of_balance -= (step.base.lambda + again.dlambda) * step.model->load_pattern();
      SpMat gap_jacobian;
      step.model->GapJacobian(u0, &gap_jacobian);
      const int k = static_cast<int>(closed.size());
      std::vector<Triplet> pick;
      pick.reserve(k);
      for (int j = 0; j < k; ++j) pick.emplace_back(j, closed[j], 1.0);
      SpMat select(k, l.nc);
      select.setFromTriplets(pick.begin(), pick.end());
      const SpMat gc = select * gap_jacobian;  // the closed pairs' rows, k x d, sparse
      // The normal matrix is only k x k (pairs closed), so a dense factorisation is cheap.
      const Mat normal = Mat(SpMat(gc * gc.transpose()));
      const Vec rc = normal.ldlt().solve(gc * out_of_balance);
      for (int j = 0; j < k; ++j) {
        if (std::isfinite(rc[j])) x[l.r() + closed[j]] = std::min(rc[j], 0.0) / step.scales.force;
      }
    }
    const SolveCounts first = result->counts;
    const std::string first_message = result->message;
    seen.push_back(active_set(x));
    summary =
        RunStepEquationSolver(solvers_.For(start), system, &x, controls, result, on_iteration);
    result->counts.iterations += first.iterations;
    result->counts.residual_evals += first.residual_evals;
    result->counts.jacobian_evals += first.jacobian_evals;
    result->counts.linear_solves += first.linear_solves;
    result->message = "restarted after: " + first_message + "; then: " + result->message;
  }
  int active = 0;
  for (bool in : seen.back()) active += in ? 1 : 0;
  result->details["active_set_size"] = std::to_string(active);
  result->details["active_set_changes"] = std::to_string(changes);
  result->details["active_set_revisits"] = std::to_string(revisits);
  result->details["nonsmooth_elements"] = std::to_string(system.nonsmooth_elements());
  if (summary.status != Status::kConverged && revisits > 0) {
    result->message += "; the active set revisited an earlier set " + std::to_string(revisits) +
                       " time(s) (cycling)";
  }
}

// --- registry factories ------------------------------------------------------------------------

std::unique_ptr<Formulation> MakeNonsmooth(ComplementarityFunction function,
                                           const FormulationConfig& config) {
  OptionReader reader(NonsmoothName(function), config.options);
  NonsmoothOptions options;
  options.restart = reader.GetBool("restart", options.restart);
  options.restart_residual = reader.GetReal("restart_residual", options.restart_residual);
  reader.Finish();
  options.function = function;
  options.solver = config.solver;
  options.solver_options = config.solver_options;
  return std::make_unique<NonsmoothFormulation>(options);
}

}  // namespace cb
