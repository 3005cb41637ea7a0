// The adapter between the Ipopt formulations (ipopt_energy.cc, ipopt_mpcc.cc) and Ipopt: the
// NLPs of ipopt_nlp.h seen as Ipopt's TNLP, Ipopt's options, one Ipopt run, and Ipopt's outcome
// mapped onto StepResult. Built only when Ipopt is found (ipopt.cmake; ipopt_stub.cc otherwise).
//
// Ipopt options set, and why (also written into settings() and the records):
//   print_level = 0, sb = yes      no output (nothing in the library prints), no banner; the
//                                  application is also created without a console journalist.
//   Initialize("")                 no ipopt.opt file is read from the working directory.
//   tol = 1e-12, constr_viol_tol = 1e-10, compl_inf_tol = 1e-10 (options `tol`,
//                                  `constr_viol_tol`, `compl_inf_tol`): the verdict is judged at
//                                  1e-8 on rows scaled as ours, times R for (29); Ipopt's default
//                                  1e-8 / 1e-4 / 1e-4 leave the barrier's complementarity and
//                                  the constraint violation above that. The final barrier
//                                  parameter is tol / 10, and P1's nearly degenerate pairs at the
//                                  edge of the contact zone need it well below the verdict's
//                                  1e-8 (docs/findings.md).
//   bound_relax_factor = 0, honor_original_bounds = yes
//                                  Ipopt relaxes every bound by 1e-8 by default, which would let
//                                  g < 0 and r > 0 by 1e-8 in the scaled variables, exactly the
//                                  verdict's tolerance: no relaxation, so g >= 0, r <= 0 hold
//                                  exactly (strictly, at interior iterates).
//   nlp_scaling_method = none      the NLPs are scaled by L and R (ipopt_nlp.h); Ipopt's
//                                  gradient-based scaling would change the meaning of `tol`.
//   mu_strategy = monotone (option `mu_strategy`, Ipopt's default): Fiacco-McCormick decrease
//                                  from mu_init, which the warm start sets (below).
//   max_iter = 300 per Ipopt run (option `max_iter`; Ipopt's default 3000): the fixtures' solves
//                                  take < 60; a run needing more is stalling, and the penalty
//                                  then retries with a larger weight (below) sooner.
//   max_cpu_time                   SolveControls::time_limit_s when set (CPU time), and the wall
//                                  clock is also checked in intermediate_callback.
//   Warm start only:
//   warm_start_init_point = yes    use the primal AND dual point given (get_starting_point).
//   warm_start_bound_push = warm_start_slack_bound_push = warm_start_mult_bound_push = 1e-9
//   warm_start_bound_frac = warm_start_slack_bound_frac = 1e-9 (option `warm_push`): Ipopt's
//                                  defaults (1e-3) move a point that sits on its bounds (g = 0
//                                  for a pair in contact, r = 0 for a free one) 1e-3 inside, i.e.
//                                  away from the answer by a thousand times the tolerance.
//   mu_init = 1e-6 (option `warm_mu_init`): a warm point is nearly complementary; starting the
//                                  barrier at the default 0.1 would first pull it to the centre.
//                                  A smaller mu_init saves an iteration per smooth step but
//                                  cannot switch a pair into contact (the two-bar truss landing
//                                  on its floor is then reported infeasible); 1e-6 lands, and
//                                  locates the kink (tests; docs/findings.md).
#pragma once

#include <exception>
#include <string>

// Ipopt's headers come through the imported pkg-config target, whose include directory CMake
// passes as -isystem: their warnings are not reported, so no pragmas are needed here.
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include "core/timer.h"
#include "formulations/common/config.h"
#include "formulations/ipopt/ipopt_nlp.h"
#include "step/formulation.h"
#include "step/time_limit.h"

namespace cb {

// The options both formulations set (defaults and reasons at the top of this file).
struct IpoptCommonOptions {
  double tol = 1e-12;
  double constr_viol_tol = 1e-10;
  double compl_inf_tol = 1e-10;
  int max_iter = 300;
  std::string mu_strategy = "monotone";
  double warm_push = 1e-9;
  double warm_mu_init = 1e-6;

  void Read(OptionReader* reader);
  // Throws std::invalid_argument naming the bad option of formulation `name`.
  void Check(const std::string& name) const;
  // The options as written into settings() and the records.
  std::string Settings() const;
};

// Ipopt's name of a return status, and what it means for the step (StepResult::status).
const char* IpoptStatusName(Ipopt::ApplicationReturnStatus s);
Status MapIpoptStatus(Ipopt::ApplicationReturnStatus s);

// A primal-dual point of an IpoptNlp (what a warm start gives Ipopt and what it returns).
struct IpoptPrimalDual {
  Vec x, z_lower, z_upper, y;
  bool has_duals = false;
};

// What ipopt-energy / ipopt-mpcc leave in StepResult::warm_state for the next step's warm
// start: the final primal-dual point of the NLP, in its own scaled variables (the driver's
// channel of the warm-state rule, src/step/warm_state.md).
struct IpoptWarmState {
  std::string formulation;  // "ipopt-energy" or "ipopt-mpcc:<reformulation>"
  ConstraintKind kind = ConstraintKind::kArcLength;
  IpoptPrimalDual point;
};

// The TNLP over an IpoptNlp. Exceptions never leave these methods into Ipopt (docs/architecture.md,
// house rule 2): they are caught, stored, the evaluation reports failure and the next
// intermediate_callback stops Ipopt; the caller rethrows after OptimizeTNLP returns.
class TnlpAdapter final : public Ipopt::TNLP {
 public:
  TnlpAdapter(IpoptNlp* nlp, const SolveControls& controls, const Stopwatch& clock,
              StepResult* result)
      : nlp_(*nlp), controls_(controls), clock_(clock), result_(*result) {}

  void set_start(const IpoptPrimalDual& start) {
    start_ = start;
    finalized_ = false;
  }
  const IpoptPrimalDual& solution() const { return solution_; }
  bool finalized() const { return finalized_; }
  std::exception_ptr error() const { return error_; }
  void set_iteration_offset(int offset) { iteration_offset_ = offset; }
  // The controls stopped the solve: the interrupt hook, or the time limit (then timed_out()).
  bool stopped_by_controls() const { return stopped_by_controls_; }
  bool timed_out() const { return timed_out_; }
  double time_limit_s() const { return controls_.time_limit_s; }
  double last_inf_pr() const { return last_inf_pr_; }
  double last_inf_du() const { return last_inf_du_; }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override {
    n = nlp_.num_variables();
    m = nlp_.num_constraints();
    nnz_jac_g = static_cast<Ipopt::Index>(nlp_.jacobian_rows().size());
    nnz_h_lag = static_cast<Ipopt::Index>(nlp_.hessian_rows().size());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override {
    std::copy_n(nlp_.x_lower().data(), n, x_l);
    std::copy_n(nlp_.x_upper().data(), n, x_u);
    std::copy_n(nlp_.c_lower().data(), m, g_l);
    std::copy_n(nlp_.c_upper().data(), m, g_u);
    return true;
  }

  bool get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x, bool init_z,
                          Ipopt::Number* z_L, Ipopt::Number* z_U, Ipopt::Index m, bool init_lambda,
                          Ipopt::Number* lambda) override {
    if (init_x) std::copy_n(start_.x.data(), n, x);
    if ((init_z || init_lambda) && !start_.has_duals) return false;
    if (init_z) {
      std::copy_n(start_.z_lower.data(), n, z_L);
      std::copy_n(start_.z_upper.data(), n, z_U);
    }
    if (init_lambda) std::copy_n(start_.y.data(), m, lambda);
    return true;
  }

  bool eval_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number& obj_value) override {
    return Guard([&] {
      ++result_.counts.residual_evals;
      return nlp_.Objective(Eigen::Map<const Vec>(x, n), &obj_value);
    });
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number* grad_f) override {
    return Guard([&] {
      if (!nlp_.Gradient(Eigen::Map<const Vec>(x, n), &work_)) return false;
      std::copy_n(work_.data(), n, grad_f);
      return true;
    });
  }

  bool eval_g(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Index m,
              Ipopt::Number* g) override {
    return Guard([&] {
      ++result_.counts.residual_evals;
      if (!nlp_.Constraints(Eigen::Map<const Vec>(x, n), &work_)) return false;
      std::copy_n(work_.data(), m, g);
      return true;
    });
  }

  bool eval_jac_g(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Index nele_jac,
                  Ipopt::Index* iRow, Ipopt::Index* jCol, Ipopt::Number* values) override {
    return Guard([&] {
      if (values == nullptr) {
        std::copy_n(nlp_.jacobian_rows().data(), nele_jac, iRow);
        std::copy_n(nlp_.jacobian_cols().data(), nele_jac, jCol);
        return true;
      }
      ++result_.counts.jacobian_evals;
      if (!nlp_.JacobianValues(Eigen::Map<const Vec>(x, n), &work_)) return false;
      std::copy_n(work_.data(), nele_jac, values);
      return true;
    });
  }

  bool eval_h(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number obj_factor,
              Ipopt::Index m, const Ipopt::Number* lambda, bool, Ipopt::Index nele_hess,
              Ipopt::Index* iRow, Ipopt::Index* jCol, Ipopt::Number* values) override {
    return Guard([&] {
      if (values == nullptr) {
        std::copy_n(nlp_.hessian_rows().data(), nele_hess, iRow);
        std::copy_n(nlp_.hessian_cols().data(), nele_hess, jCol);
        return true;
      }
      ++result_.counts.linear_solves;  // one KKT factorisation per Hessian (see DoSolve)
      if (!nlp_.HessianValues(Eigen::Map<const Vec>(x, n), obj_factor,
                              Eigen::Map<const Vec>(lambda, m), &work_)) {
        return false;
      }
      std::copy_n(work_.data(), nele_hess, values);
      return true;
    });
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index n, const Ipopt::Number* x,
                         const Ipopt::Number* z_L, const Ipopt::Number* z_U, Ipopt::Index m,
                         const Ipopt::Number*, const Ipopt::Number* lambda, Ipopt::Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution_.x = Eigen::Map<const Vec>(x, n);
    solution_.z_lower = Eigen::Map<const Vec>(z_L, n);
    solution_.z_upper = Eigen::Map<const Vec>(z_U, n);
    solution_.y = Eigen::Map<const Vec>(lambda, m);
    solution_.has_duals = true;
    finalized_ = true;
  }

  // History: merit := Ipopt's objective, residual_inf := max(inf_pr, inf_du), comp_res := NaN
  // (the iterate is not cheaply at hand here), step_length := alpha_pr. Honours SolveControls.
  bool intermediate_callback(Ipopt::AlgorithmMode, Ipopt::Index iter, Ipopt::Number obj_value,
                             Ipopt::Number inf_pr, Ipopt::Number inf_du, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number alpha_pr,
                             Ipopt::Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    if (error_) return false;
    IterationRecord record;
    record.iteration = iteration_offset_ + iter;
    record.merit = obj_value;
    record.residual_inf = std::max(inf_pr, inf_du);
    record.comp_res = std::numeric_limits<double>::quiet_NaN();
    record.step_length = alpha_pr;
    last_inf_pr_ = inf_pr;
    last_inf_du_ = inf_du;
    try {
      result_.history.push_back(record);
      timed_out_ = PastTimeLimit(controls_, clock_);
      if ((controls_.interrupted && controls_.interrupted()) || timed_out_) {
        stopped_by_controls_ = true;
        return false;
      }
    } catch (...) {
      error_ = std::current_exception();
      return false;
    }
    return true;
  }

 private:
  template <typename F>
  bool Guard(F&& body) {
    if (error_) return false;
    try {
      return body();
    } catch (...) {
      error_ = std::current_exception();
      return false;
    }
  }

  IpoptNlp& nlp_;
  const SolveControls& controls_;
  const Stopwatch& clock_;
  StepResult& result_;
  IpoptPrimalDual start_;
  IpoptPrimalDual solution_;
  bool finalized_ = false;
  bool stopped_by_controls_ = false;
  bool timed_out_ = false;
  int iteration_offset_ = 0;
  double last_inf_pr_ = 0.0, last_inf_du_ = 0.0;
  std::exception_ptr error_;
  Vec work_;
};

// An application with the options of the comment above (and the time limit of `controls`).
Ipopt::SmartPtr<Ipopt::IpoptApplication> MakeIpoptApplication(const IpoptCommonOptions& o,
                                                              const SolveControls& controls);

// The warm-start options of the comment above, with the barrier starting at mu_init.
void SetIpoptWarmStartOptions(const IpoptCommonOptions& o, double mu_init,
                              Ipopt::IpoptApplication* app);

// Runs Ipopt once; rethrows what a callback caught. Returns the raw status. The adapter is
// reference counted (Ipopt's SmartPtr), so the application may keep it as long as it likes.
Ipopt::ApplicationReturnStatus RunIpopt(Ipopt::IpoptApplication* app,
                                        const Ipopt::SmartPtr<TnlpAdapter>& adapter,
                                        StepResult* result);

// status, details["ipopt_status"], the final infeasibilities and the message of `result`.
void RecordIpoptStatus(Ipopt::ApplicationReturnStatus status, const TnlpAdapter& adapter,
                       StepResult* result);

// The previous step's final point from start.warm_state, when it is one of `formulation` with
// n variables and m constraints; else null.
const IpoptWarmState* PreviousIpoptState(const StartPoint& start, const std::string& formulation,
                                         int n, int m);

}  // namespace cb
