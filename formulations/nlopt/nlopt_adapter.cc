#include "formulations/nlopt/nlopt_adapter.h"

#include <new>
#include <sstream>
#include <stdexcept>

#include "formulations/nlopt/nlopt.h"

namespace cb {

bool NloptAvailable() { return true; }
std::string NloptVersion() {
  int major = 0, minor = 0, bugfix = 0;
  nlopt_version(&major, &minor, &bugfix);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(bugfix);
}

NloptRun::NloptRun(nlopt_algorithm algorithm, unsigned n, const SolveControls& controls,
                   StepResult* result)
    : opt_(nlopt_create(algorithm, n)),
      algorithm_(algorithm),
      controls_(controls),
      result_(result) {
  if (opt_ == nullptr) throw std::bad_alloc();
  if (controls_.time_limit_s > 0.0) nlopt_set_maxtime(opt_, controls_.time_limit_s);
}

NloptRun::~NloptRun() { nlopt_destroy(opt_); }

void NloptRun::CheckFinite(const char* what, const double* values, std::size_t m,
                           const double* grad, std::size_t size) {
  const bool finite = std::all_of(values, values + m, [](double v) { return std::isfinite(v); }) &&
                      (grad == nullptr ||
                       std::all_of(grad, grad + size, [](double v) { return std::isfinite(v); }));
  if (finite || stop_reason_ != StopReason::kNone) return;
  stop_reason_ = StopReason::kNonFinite;
  non_finite_ =
      std::string(what) + " at evaluation " + std::to_string(result_->counts.residual_evals);
  nlopt_force_stop(opt_);
}

void NloptRun::CountObjective(bool with_gradient) {
  ++result_->counts.iterations;
  ++result_->counts.residual_evals;
  if (with_gradient) ++result_->counts.jacobian_evals;
}

void NloptRun::CountConstraints(bool with_gradient) {
  ++result_->counts.residual_evals;
  if (with_gradient) ++result_->counts.jacobian_evals;
}

void NloptRun::Record(double merit, double residual_inf, double comp_res, const Vec& x) {
  IterationRecord record;
  record.iteration = result_->counts.iterations;
  record.merit = merit;
  record.residual_inf = residual_inf;
  record.comp_res = comp_res;
  record.step_length = last_x_.size() == x.size() ? (x - last_x_).norm() : 0.0;
  last_x_ = x;
  result_->history.push_back(record);
}

void NloptRun::RecordViolation(double violation) {
  if (!result_->history.empty()) result_->history.back().residual_inf = violation;
}

void NloptRun::SetStops(double ftol_rel, double xtol_rel, int maxeval) {
  CheckSetup(nlopt_set_ftol_rel(opt_, ftol_rel), "ftol_rel");
  CheckSetup(nlopt_set_xtol_rel(opt_, xtol_rel), "xtol_rel");
  CheckSetup(nlopt_set_maxeval(opt_, maxeval), "maxeval");
}

double NloptRun::Optimize(std::vector<double>* x) {
  double value = 0.0;
  const nlopt_result code = nlopt_optimize(opt_, x->data(), &value);
  if (error_) std::rethrow_exception(error_);
  Finish(code);
  return value;
}

void NloptRun::Finish(nlopt_result code) {
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
      result_->status = Status::kLimitReached;
      break;
    case NLOPT_MAXTIME_REACHED:  // only set from SolveControls::time_limit_s
      result_->status = Status::kTimeLimit;
      break;
    default:  // FAILURE, INVALID_ARGS, OUT_OF_MEMORY, ROUNDOFF_LIMITED, FORCED_STOP
      result_->status = Status::kFailed;
      break;
  }
  // A stop the controls forced decides the status whatever NLopt made of it: Luksan's LBFGS,
  // for one, reports FAILURE when its line search meets the +inf a stopped callback returns.
  // (An exception was rethrown before Finish, so no other forced stop reaches here.)
  if (stop_reason_ == StopReason::kInterrupted) result_->status = Status::kStoppedByCaller;
  if (stop_reason_ == StopReason::kTimeLimit) result_->status = Status::kTimeLimit;
  if (stop_reason_ == StopReason::kNonFinite) result_->status = Status::kFailed;
  result_->message = "NLopt " + text;
  if (result_->status == Status::kTimeLimit) {
    result_->message += " (" + TimeLimitMessage(controls_.time_limit_s) + ")";
  }
  if (stop_reason_ == StopReason::kInterrupted) result_->message += " (interrupted)";
  if (stop_reason_ == StopReason::kNonFinite) {
    result_->message += " (stopped: the model gave a non-finite " + non_finite_ + ")";
  }
  if (code == NLOPT_ROUNDOFF_LIMITED) result_->message += " (point kept; the verdict decides)";
  const char* errmsg = nlopt_get_errmsg(opt_);
  if (errmsg != nullptr) result_->message += std::string(": ") + errmsg;
}

void CheckSetup(nlopt_result code, const char* what) {
  if (code < 0) throw std::logic_error(std::string("NLopt refused ") + what);
}

std::string FormatDetail(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string DenseSlsqpRefusal(const std::string& formulation, const std::string& count,
                              int max_dense_size) {
  return formulation +
         ": LD_SLSQP is dense (O(n^2) memory, O(n^3) time per iteration) and this step has n = " +
         count + " unknowns, above max_dense_size = " + std::to_string(max_dense_size);
}

}  // namespace cb
