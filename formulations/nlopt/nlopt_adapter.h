// The adapter between the NLopt formulations (nlopt_merit.cc, nlopt_energy.cc, nlopt_mpcc.cc)
// and NLopt: one nlopt_optimize call with the counting, history, controls and status mapping of
// nlopt.h, and the frames of the callbacks NLopt calls. NLopt's C API is used directly rather
// than its C++ wrapper: the wrapper also catches exceptions in callbacks, but replaces them by
// its own std::runtime_error ("nlopt failure"); here the original exception is kept
// (std::exception_ptr) and rethrown once nlopt_optimize has returned. Built only when NLopt is
// found (nlopt.cmake; nlopt_stub.cc otherwise).
#pragma once

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <string>
#include <vector>

#include "core/timer.h"
#include "step/formulation.h"
#include "step/time_limit.h"

namespace cb {

// One nlopt_optimize call: owns the nlopt_opt, counts evaluations (NLopt has no iteration
// counter), polls the SolveControls, records the history, and keeps exceptions on the C++ side
// of NLopt's C callbacks (Guard).
class NloptRun {
 public:
  NloptRun(nlopt_algorithm algorithm, unsigned n, const SolveControls& controls,
           StepResult* result);
  ~NloptRun();
  NloptRun(const NloptRun&) = delete;
  NloptRun& operator=(const NloptRun&) = delete;

  nlopt_opt opt() const { return opt_; }

  // The frame of every objective callback: x as a Vec, `evaluate(x, gradient or null)` for the
  // value (filling the gradient when given), the gradient handed to NLopt, the evaluation
  // counted and checked, then `record(x, value)` for the history (Record). A stopped or failed
  // evaluation gives NLopt +inf and a zero gradient.
  template <class Evaluate, class RecordRow>
  double Objective(unsigned n, const double* x, double* grad, Evaluate&& evaluate,
                   RecordRow&& record) {
    double value = HUGE_VAL;
    const bool done = Guard([&] {
      x_ = Eigen::Map<const Vec>(x, n);
      value = evaluate(x_, grad != nullptr ? &gradient_ : nullptr);
      if (grad != nullptr) Eigen::Map<Vec>(grad, n) = gradient_;
      CountObjective(grad != nullptr);
      CheckFinite("objective", &value, 1, grad, n);
      record(x_, value);
    });
    if (!done) {
      if (grad != nullptr) std::fill(grad, grad + n, 0.0);
      return HUGE_VAL;
    }
    return value;
  }

  // The frame of every vector-valued constraint callback: `evaluate()` fills the m values (and
  // the dense m x n gradient when asked), the evaluation is counted and checked, and its
  // violation (max |c| of equalities, max c of inequalities c <= 0) completes the history row
  // of the objective just evaluated and goes to *violation. A stopped or failed evaluation
  // gives NLopt zeros. Returns whether `evaluate` ran to completion.
  enum class ConstraintType { kEquality, kInequality };
  template <class Evaluate>
  bool Constraints(unsigned m, double* values, unsigned n, double* grad, ConstraintType type,
                   double* violation, Evaluate&& evaluate) {
    const bool done = Guard([&] {
      evaluate();
      CountConstraints(grad != nullptr);
      CheckFinite("constraint", values, m, grad, static_cast<std::size_t>(m) * n);
      double worst = 0.0;
      for (unsigned i = 0; i < m; ++i) {
        worst =
            std::max(worst, type == ConstraintType::kEquality ? std::abs(values[i]) : values[i]);
      }
      RecordViolation(worst);
      *violation = worst;
    });
    if (!done) {
      std::fill(values, values + m, 0.0);
      if (grad != nullptr) std::fill(grad, grad + static_cast<std::size_t>(m) * n, 0.0);
    }
    return done;
  }

  // The point of the last objective evaluation (NLopt's constrained algorithms evaluate the
  // constraints right after the objective, at the same x).
  const Vec& last_x() const { return x_; }

  // One history row per objective evaluation (the counting rule of nlopt.h).
  void Record(double merit, double residual_inf, double comp_res, const Vec& x);

  // NLopt's relative tolerances and evaluation limit (throws std::logic_error if refused).
  void SetStops(double ftol_rel, double xtol_rel, int maxeval);

  // nlopt_optimize from *x, which becomes NLopt's answer; rethrows an exception caught in a
  // callback, after NLopt has returned; then the status mapping of nlopt.h,
  // details["nlopt_result"] and the message. Returns the objective at the answer.
  double Optimize(std::vector<double>* x);

 private:
  void Finish(nlopt_result code);

  enum class StopReason { kNone, kInterrupted, kTimeLimit, kNonFinite };

  // Runs `body` for a callback unless a stop is pending or the controls ask for one. Returns
  // false when `body` did not run to completion; the callback then fills its outputs with
  // harmless values (NLopt stops at its next check of the force-stop flag). Never throws.
  template <class Body>
  bool Guard(Body&& body) noexcept {
    if (error_ || stop_reason_ != StopReason::kNone) return false;
    try {
      if (controls_.interrupted && controls_.interrupted()) {
        stop_reason_ = StopReason::kInterrupted;
      } else if (PastTimeLimit(controls_, clock_)) {
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
  // run on to maxeval). Called inside a Guard body with what was just computed.
  void CheckFinite(const char* what, const double* values, std::size_t m, const double* grad,
                   std::size_t size);
  // Counting rule (nlopt.h): iterations = objective evaluations.
  void CountObjective(bool with_gradient);
  void CountConstraints(bool with_gradient);
  // The constraint violation at the point the objective was just evaluated at.
  void RecordViolation(double violation);

  nlopt_opt opt_;
  nlopt_algorithm algorithm_;
  const SolveControls& controls_;
  StepResult* result_;
  Stopwatch clock_;
  std::exception_ptr error_;
  StopReason stop_reason_ = StopReason::kNone;
  std::string non_finite_;  // what was not finite, for the message
  Vec last_x_;              // the previous recorded point (step_length)
  Vec x_, gradient_;        // the objective's point and gradient
};

// Throws std::logic_error when NLopt refuses a setting (`what`) of the run.
void CheckSetup(nlopt_result code, const char* what);

// A number in details[], as an ostream writes it.
std::string FormatDetail(double v);

// The reason LD_SLSQP, which is dense, refuses a step whose unknowns (`count`, e.g.
// "d + 2 nc + 1 = 5407") exceed max_dense_size.
std::string DenseSlsqpRefusal(const std::string& formulation, const std::string& count,
                              int max_dense_size);

}  // namespace cb
