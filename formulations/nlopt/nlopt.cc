// The NLopt formulations (see nlopt.h for what they count and report). NLopt's C API is used
// directly rather than its C++ wrapper: the wrapper also catches exceptions in callbacks, but
// replaces them by its own std::runtime_error ("nlopt failure"); here the original exception is
// kept (std::exception_ptr) and rethrown once nlopt_optimize has returned.
#include "formulations/nlopt/nlopt.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/timer.h"
#include "formulations/nlopt/nlopt_problems.h"

#ifdef CONTACTBENCH_HAVE_NLOPT
#include <nlopt.h>
#endif

namespace cb {

// --- options -------------------------------------------------------------------------------

namespace {

bool Positive(double v) { return v > 0.0 && std::isfinite(v); }
bool NonNegative(double v) { return v >= 0.0 && std::isfinite(v); }

}  // namespace

bool NloptMeritOptions::IsValid(std::string* why) const {
  if (algorithm != "lbfgs" && algorithm != "tnewton") {
    *why = "algorithm must be lbfgs or tnewton";
  } else if (static_cast<int>(eta) < 1 || static_cast<int>(eta) > 4) {
    *why = "eta must be 1, 2, 3 or 4";
  } else if (!(gamma_tol > 0.0 && gamma_tol < 1.0)) {
    *why = "gamma_tol must be in (0, 1)";
  } else if (!Positive(rho_min)) {
    *why = "rho_min must be positive";
  } else if (!Positive(residual_tol)) {
    *why = "residual_tol must be positive";
  } else if (!Positive(merit_scale)) {
    *why = "merit_scale must be positive";
  } else if (!NonNegative(ftol_rel) || !NonNegative(xtol_rel)) {
    *why = "ftol_rel and xtol_rel must be >= 0";
  } else if (maxeval < 1) {
    *why = "maxeval must be >= 1";
  } else if (memory < 0) {
    *why = "memory must be >= 0";
  } else {
    return true;
  }
  return false;
}

bool NloptEnergyOptions::IsValid(std::string* why) const {
  if (algorithm != "mma" && algorithm != "ccsaq" && algorithm != "slsqp") {
    *why = "algorithm must be mma, ccsaq or slsqp";
  } else if (!NonNegative(ftol_rel) || !NonNegative(xtol_rel)) {
    *why = "ftol_rel and xtol_rel must be >= 0";
  } else if (!NonNegative(constraint_tol)) {
    *why = "constraint_tol must be >= 0";
  } else if (maxeval < 1) {
    *why = "maxeval must be >= 1";
  } else if (!NonNegative(active_tol)) {
    *why = "active_tol must be >= 0";
  } else if (max_dense_size < 1) {
    *why = "max_dense_size must be >= 1";
  } else if (!Positive(max_gradient_entries)) {
    *why = "max_gradient_entries must be positive";
  } else {
    return true;
  }
  return false;
}

bool NloptMpccOptions::IsValid(std::string* why) const {
  if (!Positive(weight)) {
    *why = "weight must be positive";
  } else if (!Positive(bound_push)) {
    *why = "bound_push must be positive";
  } else if (!Positive(residual_tol)) {
    *why = "residual_tol must be positive";
  } else if (!NonNegative(ftol_rel) || !NonNegative(xtol_rel)) {
    *why = "ftol_rel and xtol_rel must be >= 0";
  } else if (maxeval < 1) {
    *why = "maxeval must be >= 1";
  } else if (max_dense_size < 1) {
    *why = "max_dense_size must be >= 1";
  } else {
    return true;
  }
  return false;
}

namespace {

[[maybe_unused]] std::string Number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

template <class Options>
void Check(const std::string& name, const Options& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(name + " options: " + why);
}

NloptMeritOptions ReadMeritOptions(const FormulationConfig& config) {
  if (config.eta < 1 || config.eta > 4) {
    throw std::invalid_argument("nlopt-merit: eta must be 1, 2, 3 or 4 (got " +
                                std::to_string(config.eta) + ")");
  }
  OptionReader reader("nlopt-merit", config.options);
  NloptMeritOptions o;
  o.eta = static_cast<EtaCase>(config.eta);
  o.algorithm = reader.GetChoice("algorithm", o.algorithm, {"lbfgs", "tnewton"});
  o.gamma_tol = reader.GetReal("gamma_tol", o.gamma_tol);
  o.rho_min = reader.GetReal("rho_min", o.rho_min);
  o.residual_tol = reader.GetReal("residual_tol", config.solver_options.residual_tol);
  o.merit_scale = reader.GetReal("merit_scale", o.merit_scale);
  o.ftol_rel = reader.GetReal("ftol_rel", o.ftol_rel);
  o.xtol_rel = reader.GetReal("xtol_rel", o.xtol_rel);
  o.maxeval = reader.GetInteger("maxeval", o.maxeval);
  o.memory = reader.GetInteger("memory", o.memory);
  reader.Finish();
  Check("nlopt-merit", o);
  return o;
}

NloptEnergyOptions ReadEnergyOptions(const FormulationConfig& config) {
  OptionReader reader("nlopt-energy", config.options);
  NloptEnergyOptions o;
  o.algorithm = reader.GetChoice("algorithm", o.algorithm, {"mma", "ccsaq", "slsqp"});
  o.ftol_rel = reader.GetReal("ftol_rel", o.ftol_rel);
  o.xtol_rel = reader.GetReal("xtol_rel", o.xtol_rel);
  o.constraint_tol = reader.GetReal("constraint_tol", o.constraint_tol);
  o.maxeval = reader.GetInteger("maxeval", o.maxeval);
  o.active_tol = reader.GetReal("active_tol", o.active_tol);
  o.max_dense_size = reader.GetInteger("max_dense_size", o.max_dense_size);
  o.max_gradient_entries = reader.GetReal("max_gradient_entries", o.max_gradient_entries);
  reader.Finish();
  Check("nlopt-energy", o);
  return o;
}

NloptMpccOptions ReadMpccOptions(const FormulationConfig& config) {
  OptionReader reader("nlopt-mpcc", config.options);
  NloptMpccOptions o;
  o.weight = reader.GetReal("weight", o.weight);
  o.residual_tol = reader.GetReal("residual_tol", o.residual_tol);
  o.ftol_rel = reader.GetReal("ftol_rel", o.ftol_rel);
  o.xtol_rel = reader.GetReal("xtol_rel", o.xtol_rel);
  o.maxeval = reader.GetInteger("maxeval", o.maxeval);
  o.bound_push = reader.GetReal("bound_push", o.bound_push);
  o.max_dense_size = reader.GetInteger("max_dense_size", o.max_dense_size);
  reader.Finish();
  Check("nlopt-mpcc", o);
  return o;
}

}  // namespace

#ifndef CONTACTBENCH_HAVE_NLOPT

bool NloptAvailable() { return false; }
// The options are still read, so that a bad option is reported as such in every build.
std::unique_ptr<Formulation> MakeNloptMerit(const FormulationConfig& config) {
  ReadMeritOptions(config);
  throw std::invalid_argument("nlopt-merit: NLopt was not found when this build was configured");
}
std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig& config) {
  ReadEnergyOptions(config);
  throw std::invalid_argument("nlopt-energy: NLopt was not found when this build was configured");
}
std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig& config) {
  ReadMpccOptions(config);
  throw std::invalid_argument("nlopt-mpcc: NLopt was not found when this build was configured");
}

#else  // CONTACTBENCH_HAVE_NLOPT

bool NloptAvailable() { return true; }

namespace {

// One nlopt_optimize call: owns the nlopt_opt, counts evaluations (NLopt has no iteration
// counter), polls the SolveControls, records the history, and keeps exceptions on the C++ side
// of NLopt's C callbacks (Guard).
class NloptRun {
 public:
  NloptRun(nlopt_algorithm algorithm, unsigned n, const SolveControls& controls, StepResult* result)
      : opt_(nlopt_create(algorithm, n)),
        algorithm_(algorithm),
        controls_(controls),
        result_(result) {
    if (opt_ == nullptr) throw std::bad_alloc();
    if (controls_.time_limit_s > 0.0) nlopt_set_maxtime(opt_, controls_.time_limit_s);
  }
  ~NloptRun() { nlopt_destroy(opt_); }
  NloptRun(const NloptRun&) = delete;
  NloptRun& operator=(const NloptRun&) = delete;

  nlopt_opt opt() const { return opt_; }

  // Runs `body` for a callback unless a stop is pending or the controls ask for one. Returns
  // false when `body` did not run to completion; the callback then fills its outputs with
  // harmless values (NLopt stops at its next check of the force-stop flag). Never throws.
  template <class Body>
  bool Guard(Body&& body) noexcept {
    if (error_ || stop_reason_ != StopReason::kNone) return false;
    try {
      if (controls_.interrupted && controls_.interrupted()) {
        stop_reason_ = StopReason::kInterrupted;
      } else if (controls_.time_limit_s > 0.0 && clock_.Seconds() > controls_.time_limit_s) {
        stop_reason_ = StopReason::kTimeLimit;
      }
      if (stop_reason_ != StopReason::kNone) {
        nlopt_force_stop(opt_);
        return false;
      }
      body();
      return true;
    } catch (...) {
      error_ = std::current_exception();
      nlopt_force_stop(opt_);
      return false;
    }
  }

  // A non-finite value from the model stops the run as a failure with that reason: NLopt's
  // algorithms do not handle NaN (LBFGS has reported SUCCESS at a NaN objective, MMA and SLSQP
  // run on to maxeval). Call inside a Guard body with what was just computed.
  void CheckFinite(const char* what, const double* values, std::size_t m, const double* grad,
                   std::size_t size) {
    const bool finite =
        std::all_of(values, values + m, [](double v) { return std::isfinite(v); }) &&
        (grad == nullptr ||
         std::all_of(grad, grad + size, [](double v) { return std::isfinite(v); }));
    if (finite || stop_reason_ != StopReason::kNone) return;
    stop_reason_ = StopReason::kNonFinite;
    non_finite_ =
        std::string(what) + " at evaluation " + std::to_string(result_->counts.residual_evals);
    nlopt_force_stop(opt_);
  }

  // Counting rule (nlopt.h): iterations = objective evaluations.
  void CountObjective(bool with_gradient) {
    ++result_->counts.iterations;
    ++result_->counts.residual_evals;
    if (with_gradient) ++result_->counts.jacobian_evals;
  }
  void CountConstraints(bool with_gradient) {
    ++result_->counts.residual_evals;
    if (with_gradient) ++result_->counts.jacobian_evals;
  }

  // One history row per objective evaluation.
  void Record(double merit, double residual_inf, double comp_res, const Vec& x) {
    IterationRecord record;
    record.iteration = result_->counts.iterations;
    record.merit = merit;
    record.residual_inf = residual_inf;
    record.comp_res = comp_res;
    record.step_length = last_x_.size() == x.size() ? (x - last_x_).norm() : 0.0;
    last_x_ = x;
    result_->history.push_back(record);
  }
  // The constraint violation at the point the objective was just evaluated at (NLopt's
  // constrained algorithms evaluate the constraints right after the objective, same x).
  void RecordViolation(double violation) {
    if (!result_->history.empty()) result_->history.back().residual_inf = violation;
  }

  // nlopt_optimize; rethrows an exception caught in a callback, after NLopt has returned.
  nlopt_result Optimize(std::vector<double>* x, double* value) {
    const nlopt_result code = nlopt_optimize(opt_, x->data(), value);
    if (error_) std::rethrow_exception(error_);
    return code;
  }

  // Status mapping of nlopt.h, details["nlopt_result"], the message.
  void Finish(nlopt_result code) {
    const char* name = nlopt_result_to_string(code);
    const std::string text = name != nullptr ? name : "UNKNOWN";
    result_->details["nlopt_result"] = std::to_string(static_cast<int>(code)) + " " + text;
    result_->details["nlopt_algorithm"] = nlopt_algorithm_to_string(algorithm_);
    result_->details["evaluations"] = std::to_string(result_->counts.iterations);
    switch (code) {
      case NLOPT_SUCCESS:
      case NLOPT_STOPVAL_REACHED:
      case NLOPT_FTOL_REACHED:
      case NLOPT_XTOL_REACHED:
        result_->status = Status::kConverged;
        break;
      case NLOPT_MAXEVAL_REACHED:
      case NLOPT_MAXTIME_REACHED:
        result_->status = Status::kLimitReached;
        break;
      default:  // FAILURE, INVALID_ARGS, OUT_OF_MEMORY, ROUNDOFF_LIMITED, FORCED_STOP
        result_->status = Status::kFailed;
        break;
    }
    // A stop the controls forced decides the status whatever NLopt made of it: Luksan's LBFGS,
    // for one, reports FAILURE when its line search meets the +inf a stopped callback returns.
    // (An exception was rethrown before Finish, so no other forced stop reaches here.)
    if (stop_reason_ == StopReason::kInterrupted) result_->status = Status::kStoppedByCaller;
    if (stop_reason_ == StopReason::kTimeLimit) result_->status = Status::kLimitReached;
    if (stop_reason_ == StopReason::kNonFinite) result_->status = Status::kFailed;
    result_->message = "NLopt " + text;
    if (stop_reason_ == StopReason::kTimeLimit) result_->message += " (time limit)";
    if (stop_reason_ == StopReason::kInterrupted) result_->message += " (interrupted)";
    if (stop_reason_ == StopReason::kNonFinite) {
      result_->message += " (stopped: the model gave a non-finite " + non_finite_ + ")";
    }
    if (code == NLOPT_ROUNDOFF_LIMITED) result_->message += " (point kept; the verdict decides)";
    const char* errmsg = nlopt_get_errmsg(opt_);
    if (errmsg != nullptr) result_->message += std::string(": ") + errmsg;
  }

 private:
  enum class StopReason { kNone, kInterrupted, kTimeLimit, kNonFinite };
  nlopt_opt opt_;
  nlopt_algorithm algorithm_;
  const SolveControls& controls_;
  StepResult* result_;
  Stopwatch clock_;
  std::exception_ptr error_;
  StopReason stop_reason_ = StopReason::kNone;
  std::string non_finite_;  // what was not finite, for the message
  Vec last_x_;
};

void CheckSetup(nlopt_result code, const char* what) {
  if (code < 0) throw std::logic_error(std::string("NLopt refused ") + what);
}

// ||min(g^, -r^)||_inf over the pairs, for the history.
double CompRes(const Vec& x, int g0, int r0, int nc) {
  double comp = 0.0;
  for (int p = 0; p < nc; ++p) comp = std::max(comp, std::abs(std::min(x[g0 + p], -x[r0 + p])));
  return comp;
}

// --- nlopt-merit ---------------------------------------------------------------------------

struct MeritData {
  NloptRun* run;
  NloptMeritObjective* objective;
  Vec x, gradient, best_x;
  double best_value = std::numeric_limits<double>::infinity();
};

double MeritCallback(unsigned n, const double* x, double* grad, void* data) {
  auto& d = *static_cast<MeritData*>(data);
  double value = HUGE_VAL;
  const bool done = d.run->Guard([&] {
    d.x = Eigen::Map<const Vec>(x, n);
    value = d.objective->Evaluate(d.x, grad != nullptr ? &d.gradient : nullptr);
    if (grad != nullptr) Eigen::Map<Vec>(grad, n) = d.gradient;
    d.run->CountObjective(grad != nullptr);
    d.run->CheckFinite("objective", &value, 1, grad, n);
    const ImplicitFbLayout& l = d.objective->layout();
    const Vec& f = d.objective->residual();
    const Vec x = d.objective->FromNlopt(d.x);
    d.run->Record(d.objective->merit(), f.allFinite() ? f.lpNorm<Eigen::Infinity>() : HUGE_VAL,
                  CompRes(x, l.g(), l.r(), l.nc), x);
    if (value < d.best_value) {
      d.best_value = value;
      d.best_x = x;
    }
  });
  if (!done) {
    if (grad != nullptr) std::fill(grad, grad + n, 0.0);
    return HUGE_VAL;
  }
  return value;
}

class NloptMerit final : public Formulation {
 public:
  explicit NloptMerit(NloptMeritOptions options) : options_(std::move(options)) {
    Check("nlopt-merit", options_);
  }
  std::string name() const override { return "nlopt-merit"; }
  std::string solver() const override { return "nlopt-" + options_.algorithm; }
  std::string settings() const override {
    std::ostringstream out;
    out << "algorithm=" << options_.algorithm << ";eta=" << static_cast<int>(options_.eta)
        << ";residual_tol=" << options_.residual_tol << ";merit_scale=" << options_.merit_scale
        << ";maxeval=" << options_.maxeval << ";iterations=evaluations";
    return out.str();
  }
  bool Supports(ConstraintKind) const override { return true; }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    ImplicitFbOptions start_options;
    start_options.eta = options_.eta;
    start_options.gamma_tol = options_.gamma_tol;
    start_options.rho_min = options_.rho_min;
    const ImplicitFbStart initial = MakeImplicitFbStart(step, start, start_options);
    NloptMeritObjective objective(step, EtaEquation{options_.eta, initial.gamma},
                                  options_.merit_scale);
    const ImplicitFbLayout& l = objective.layout();
    const unsigned n = static_cast<unsigned>(l.size());

    NloptRun run(options_.algorithm == "tnewton" ? NLOPT_LD_TNEWTON : NLOPT_LD_LBFGS, n, controls,
                 result);
    MeritData data{&run, &objective, Vec(), Vec(), initial.x};
    nlopt_opt opt = run.opt();
    CheckSetup(nlopt_set_min_objective(opt, MeritCallback, &data), "the objective");
    // stopval: s/2 ||F||^2 <= s/2 tol^2 implies ||F||_inf <= tol.
    const double tol = options_.residual_tol;
    CheckSetup(nlopt_set_stopval(opt, 0.5 * options_.merit_scale * tol * tol), "stopval");
    CheckSetup(nlopt_set_ftol_rel(opt, options_.ftol_rel), "ftol_rel");
    CheckSetup(nlopt_set_xtol_rel(opt, options_.xtol_rel), "xtol_rel");
    CheckSetup(nlopt_set_maxeval(opt, options_.maxeval), "maxeval");
    if (options_.memory > 0) {
      CheckSetup(nlopt_set_vector_storage(opt, static_cast<unsigned>(options_.memory)), "memory");
    }
    const Vec y0 = objective.ToNlopt(initial.x);
    std::vector<double> y(y0.data(), y0.data() + n);
    double value = 0.0;
    const nlopt_result code = run.Optimize(&y, &value);
    run.Finish(code);

    // The answer: the evaluated point of least merit (what LBFGS returns, kept here too so that
    // a forced or failed stop still hands back its best point).
    Vec best = objective.FromNlopt(Eigen::Map<const Vec>(y.data(), n));
    if (!(value <= data.best_value)) best = data.best_x;
    result->point.du = best.segment(l.du(), l.d);
    result->point.g = step.scales.length * best.segment(l.g(), l.nc);
    result->point.r = step.scales.force * best.segment(l.r(), l.nc);
    result->point.dlambda = best[l.dlambda()];
    result->details["gamma"] = Number(initial.gamma);
    result->details["rho0"] = Number(initial.x[l.rho()]);
    result->details["rho"] = Number(best[l.rho()]);
    result->details["final_merit"] =
        Number(std::min(value, data.best_value) / options_.merit_scale);
  }

  NloptMeritOptions options_;
};

// --- nlopt-energy --------------------------------------------------------------------------

struct EnergyData {
  NloptRun* run;
  const NloptEnergyProblem* problem;
  double constraint_tol;
  Vec y, gradient;
  double value = HUGE_VAL;  // the objective at y
  // The evaluated point of least objective whose violation max_p phi_p / L is within
  // constraint_tol (see NloptEnergy::DoSolve).
  Vec best_y;
  double best_value = HUGE_VAL;
};

double EnergyObjective(unsigned n, const double* y, double* grad, void* data) {
  auto& d = *static_cast<EnergyData*>(data);
  double value = HUGE_VAL;
  const bool done = d.run->Guard([&] {
    d.y = Eigen::Map<const Vec>(y, n);
    value = d.problem->Objective(d.y, grad != nullptr ? &d.gradient : nullptr);
    d.value = value;
    if (grad != nullptr) Eigen::Map<Vec>(grad, n) = d.gradient;
    d.run->CountObjective(grad != nullptr);
    d.run->CheckFinite("objective", &value, 1, grad, n);
    d.run->Record(value, std::numeric_limits<double>::quiet_NaN(),
                  std::numeric_limits<double>::quiet_NaN(), d.y);
  });
  if (!done) {
    if (grad != nullptr) std::fill(grad, grad + n, 0.0);
    return HUGE_VAL;
  }
  return value;
}

void EnergyConstraints(unsigned m, double* values, unsigned n, const double* y, double* grad,
                       void* data) {
  auto& d = *static_cast<EnergyData*>(data);
  const bool done = d.run->Guard([&] {
    d.problem->Constraints(Eigen::Map<const Vec>(y, n), values, grad);
    d.run->CountConstraints(grad != nullptr);
    d.run->CheckFinite("constraint", values, m, grad, static_cast<std::size_t>(m) * n);
    double violation = 0.0;
    for (unsigned p = 0; p < m; ++p) violation = std::max(violation, values[p]);
    d.run->RecordViolation(violation);
    const bool same_point = d.y.size() == n && d.y == Eigen::Map<const Vec>(y, n);
    if (same_point && violation <= d.constraint_tol && d.value < d.best_value) {
      d.best_value = d.value;
      d.best_y = d.y;
    }
  });
  if (!done) {
    std::fill(values, values + m, 0.0);
    if (grad != nullptr) std::fill(grad, grad + static_cast<std::size_t>(m) * n, 0.0);
  }
}

nlopt_algorithm EnergyAlgorithm(const std::string& name) {
  if (name == "ccsaq") return NLOPT_LD_CCSAQ;
  if (name == "slsqp") return NLOPT_LD_SLSQP;
  return NLOPT_LD_MMA;
}

class NloptEnergy final : public Formulation {
 public:
  explicit NloptEnergy(NloptEnergyOptions options) : options_(std::move(options)) {
    Check("nlopt-energy", options_);
  }
  std::string name() const override { return "nlopt-energy"; }
  std::string solver() const override { return "nlopt-" + options_.algorithm; }
  std::string settings() const override {
    std::ostringstream out;
    out << "algorithm=" << options_.algorithm << ";ftol_rel=" << options_.ftol_rel
        << ";xtol_rel=" << options_.xtol_rel << ";constraint_tol=" << options_.constraint_tol
        << ";active_tol=" << options_.active_tol << ";maxeval=" << options_.maxeval
        << ";iterations=evaluations";
    return out.str();
  }
  bool Supports(ConstraintKind kind) const override { return kind == ConstraintKind::kFixedLoad; }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    const NloptEnergyProblem problem(step);  // refuses models without an energy
    const int d = problem.size();
    const int nc = problem.num_constraints();
    if (options_.algorithm == "slsqp" && d > options_.max_dense_size) {
      throw std::invalid_argument(
          "nlopt-energy: LD_SLSQP is dense (O(n^2) memory, O(n^3) time per iteration) and this "
          "step has n = " +
          std::to_string(d) + " unknowns, above max_dense_size = " +
          std::to_string(options_.max_dense_size) + " (use algorithm=mma or ccsaq)");
    }
    if (static_cast<double>(nc) * d > options_.max_gradient_entries) {
      throw std::invalid_argument(
          "nlopt-energy: NLopt's vector-valued constraint needs a dense " + std::to_string(nc) +
          " x " + std::to_string(d) +
          " gradient, above max_gradient_entries = " + Number(options_.max_gradient_entries));
    }
    // Warm: the increment the driver predicts (du = 0 for its fixed-load steps); cold: du = 0.
    Vec y0 = Vec::Zero(d);
    if (start.kind == StartKind::kWarm) y0 = start.du / step.scales.length;

    NloptRun run(EnergyAlgorithm(options_.algorithm), static_cast<unsigned>(d), controls, result);
    EnergyData data{&run,  &problem, options_.constraint_tol, Vec(), Vec(), HUGE_VAL,
                    Vec(), HUGE_VAL};
    nlopt_opt opt = run.opt();
    CheckSetup(nlopt_set_min_objective(opt, EnergyObjective, &data), "the objective");
    if (nc > 0) {
      const std::vector<double> tol(nc, options_.constraint_tol);
      CheckSetup(nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(nc), EnergyConstraints,
                                                  &data, tol.data()),
                 "the gap constraints");
    }
    CheckSetup(nlopt_set_ftol_rel(opt, options_.ftol_rel), "ftol_rel");
    CheckSetup(nlopt_set_xtol_rel(opt, options_.xtol_rel), "xtol_rel");
    CheckSetup(nlopt_set_maxeval(opt, options_.maxeval), "maxeval");
    std::vector<double> y(y0.data(), y0.data() + d);
    double value = 0.0;
    const nlopt_result code = run.Optimize(&y, &value);
    run.Finish(code);

    // The answer. MMA and CCSAQ may return a point that violates the constraints by more than
    // their tolerance (NLopt's mma.c accepts an infeasible point of lower objective once its
    // conservative inner iteration is done); the verdict demands feasibility, so such a point is
    // replaced by the best evaluated point within constraint_tol, when there is one.
    Vec answer = Eigen::Map<const Vec>(y.data(), d);
    if (nc > 0) {
      Vec c(nc);
      problem.Constraints(answer, c.data(), nullptr);
      const double violation = c.maxCoeff();
      if (violation > options_.constraint_tol && data.best_y.size() == d) {
        answer = data.best_y;
        value = data.best_value;
        result->details["answer"] =
            "best feasible evaluation (NLopt's point violates by " + Number(violation) + ")";
      }
    }
    int active = 0;
    result->point = problem.Recover(answer, options_.active_tol, &active);
    result->details["active_pairs"] = std::to_string(active);
    result->details["final_objective"] = Number(value);
    result->details["reactions"] = "least squares on the active pairs (NLopt has no multipliers)";
  }

  NloptEnergyOptions options_;
};

// --- nlopt-mpcc ----------------------------------------------------------------------------

struct MpccData {
  NloptRun* run;
  NloptMpccProblem* problem;
  Vec z, gradient;
};

double MpccObjective(unsigned n, const double* z, double* grad, void* data) {
  auto& d = *static_cast<MpccData*>(data);
  double value = HUGE_VAL;
  const bool done = d.run->Guard([&] {
    d.z = Eigen::Map<const Vec>(z, n);
    value = d.problem->Objective(d.z, grad != nullptr ? &d.gradient : nullptr);
    if (grad != nullptr) Eigen::Map<Vec>(grad, n) = d.gradient;
    d.run->CountObjective(grad != nullptr);
    d.run->CheckFinite("objective", &value, 1, grad, n);
    const ImplicitFbLayout& l = d.problem->layout();
    d.run->Record(value, std::numeric_limits<double>::quiet_NaN(), CompRes(d.z, l.g(), l.r(), l.nc),
                  d.z);
  });
  if (!done) {
    if (grad != nullptr) std::fill(grad, grad + n, 0.0);
    return HUGE_VAL;
  }
  return value;
}

void MpccEqualities(unsigned m, double* values, unsigned n, const double* z, double* grad,
                    void* data) {
  auto& d = *static_cast<MpccData*>(data);
  const bool done = d.run->Guard([&] {
    d.problem->Equalities(Eigen::Map<const Vec>(z, n), values, grad);
    d.run->CountConstraints(grad != nullptr);
    d.run->CheckFinite("constraint", values, m, grad, static_cast<std::size_t>(m) * n);
    double violation = 0.0;
    for (unsigned i = 0; i < m; ++i) violation = std::max(violation, std::abs(values[i]));
    d.run->RecordViolation(violation);
  });
  if (!done) {
    std::fill(values, values + m, 0.0);
    if (grad != nullptr) std::fill(grad, grad + static_cast<std::size_t>(m) * n, 0.0);
  }
}

class NloptMpcc final : public Formulation {
 public:
  explicit NloptMpcc(const NloptMpccOptions& options) : options_(options) {
    Check("nlopt-mpcc", options_);
  }
  std::string name() const override { return "nlopt-mpcc"; }
  std::string solver() const override { return "nlopt-slsqp"; }
  std::string settings() const override {
    std::ostringstream out;
    out << "algorithm=slsqp;weight=" << options_.weight << ";residual_tol=" << options_.residual_tol
        << ";maxeval=" << options_.maxeval << ";iterations=evaluations";
    return out.str();
  }
  bool Supports(ConstraintKind) const override { return true; }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    const ImplicitFbLayout layout{step.num_dofs(), step.num_pairs()};
    const int n = layout.size() - 1;
    if (n > options_.max_dense_size) {
      throw std::invalid_argument(
          "nlopt-mpcc: LD_SLSQP is dense (O(n^2) memory, O(n^3) time per iteration) and this "
          "step has n = d + 2 nc + 1 = " +
          std::to_string(n) +
          " unknowns, above max_dense_size "
          "= " +
          std::to_string(options_.max_dense_size));
    }
    NloptMpccProblem problem(step, options_.weight);
    const int m = problem.num_equalities();

    // Start (nlopt.h): the implicit formulation's, onto the bounds.
    ImplicitFbOptions start_options;
    start_options.eta = EtaCase::kNonsmooth;  // rho is not an unknown here
    const ImplicitFbStart initial = MakeImplicitFbStart(step, start, start_options);
    Vec z0 = initial.x.head(n);
    for (int p = 0; p < layout.nc; ++p) {
      double& g = z0[layout.g() + p];
      double& r = z0[layout.r() + p];
      if (start.kind == StartKind::kCold) {
        g = 1.0;
        r = -1.0;
      } else {
        // Strictly inside the bounds: a start on both bounds (g^ = r^ = 0, e.g. a pair about
        // to touch, whose r^k = 0 and predicted gap <= 0) is the MPCC's degenerate corner,
        // where SLSQP's subproblem (equalities plus both active bounds) is rank-deficient and
        // it stops at once with ROUNDOFF_LIMITED.
        g = std::max(g, options_.bound_push);
        r = std::min(r, -options_.bound_push);
      }
    }

    NloptRun run(NLOPT_LD_SLSQP, static_cast<unsigned>(n), controls, result);
    MpccData data{&run, &problem, Vec(), Vec()};
    nlopt_opt opt = run.opt();
    std::vector<double> lower, upper;
    problem.Bounds(&lower, &upper);
    CheckSetup(nlopt_set_lower_bounds(opt, lower.data()), "the lower bounds");
    CheckSetup(nlopt_set_upper_bounds(opt, upper.data()), "the upper bounds");
    CheckSetup(nlopt_set_min_objective(opt, MpccObjective, &data), "the objective");
    const std::vector<double> tol(m, options_.residual_tol);
    CheckSetup(nlopt_add_equality_mconstraint(opt, static_cast<unsigned>(m), MpccEqualities, &data,
                                              tol.data()),
               "the equality rows");
    const double t = options_.residual_tol;
    CheckSetup(nlopt_set_stopval(opt, options_.weight * t * t), "stopval");
    CheckSetup(nlopt_set_ftol_rel(opt, options_.ftol_rel), "ftol_rel");
    CheckSetup(nlopt_set_xtol_rel(opt, options_.xtol_rel), "xtol_rel");
    CheckSetup(nlopt_set_maxeval(opt, options_.maxeval), "maxeval");
    std::vector<double> z(z0.data(), z0.data() + n);
    double value = 0.0;
    const nlopt_result code = run.Optimize(&z, &value);
    run.Finish(code);

    result->point = problem.Point(Eigen::Map<const Vec>(z.data(), n));
    result->details["final_objective"] = Number(value);
  }

  NloptMpccOptions options_;
};

}  // namespace

std::unique_ptr<Formulation> MakeNloptMerit(const FormulationConfig& config) {
  return std::make_unique<NloptMerit>(ReadMeritOptions(config));
}
std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig& config) {
  return std::make_unique<NloptEnergy>(ReadEnergyOptions(config));
}
std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig& config) {
  return std::make_unique<NloptMpcc>(ReadMpccOptions(config));
}

#endif  // CONTACTBENCH_HAVE_NLOPT

}  // namespace cb
