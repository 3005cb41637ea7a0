// The Ipopt formulations (issue 3): `ipopt-energy` and `ipopt-mpcc`. The NLPs themselves are in
// ipopt_nlp.{h,cc}; this file adapts them to Ipopt's TNLP, sets Ipopt's options, builds the
// cold and warm starts and maps Ipopt's outcome onto StepResult.
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
//                                  parameter is tol / 10: with tol = 1e-10 P1's nearly degenerate
//                                  pairs at the edge of the contact zone ended at
//                                  min(g/L, -r/R) = 4e-9, too close to 1e-8; 1e-12 gives 1e-10
//                                  at the same iteration counts.
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
//                                  1e-9 saves an iteration per smooth step (2 instead of 3 on
//                                  arch-curved) but cannot switch a pair into contact: on the
//                                  two-bar truss landing on its floor Ipopt then reports
//                                  Infeasible_Problem_Detected until the arc length is cut to
//                                  nothing; 1e-6 lands, and locates the kink (tests).
//
// ipopt-mpcc options (FormulationConfig::options):
//   reformulation = penalty (default) | scholtes
//     penalty: objective penalty_weight * sum_p (-g^_p r^_p) (default weight 1), one Ipopt solve,
//       repeated with 10x the weight while Ipopt does not converge, up to penalty_max_weight (100);
//       on the fixtures it needs 2-3 Ipopt iterations per warm arc-length step, Scholtes 30-60.
//     scholtes: -g^_p r^_p <= t, t = scholtes_t0 (1; scholtes_warm_t0 = 1e-6 on warm steps) times
//       scholtes_factor (0.1) per subproblem down to scholtes_t_min (1e-12), the floor: with
//       a zero objective the barrier centres g^ r^ near -t/2, so min(g^, -r^) ~ t / max(...), and
//       the verdict's 1e-8 needs t well below it also for pairs with g^, -r^ ~ 1e-3 near a kink.
//       Each subproblem is warm started from the previous one with mu_init = scholtes_mu_init
//       (1e-9; the previous answer is at most a factor 10 in t away).
// The cold start is g^ = 1, r^ = -1, du = 0 (see IpoptMpcc::MakeStart); the warm start is the
// previous primal point (38)-(41) and the previous step's multipliers from warm_state.
#include "formulations/ipopt/ipopt.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/timer.h"
#include "formulations/ipopt/ipopt_nlp.h"

#ifdef CONTACTBENCH_HAVE_IPOPT
// Ipopt's headers come through the imported pkg-config target, whose include directory CMake
// passes as -isystem: their warnings are not reported, so no pragmas are needed here.
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#endif

namespace cb {

#ifndef CONTACTBENCH_HAVE_IPOPT

bool IpoptAvailable() { return false; }
std::unique_ptr<Formulation> MakeIpoptEnergy(const FormulationConfig&) {
  throw std::invalid_argument("ipopt-energy: this build has no Ipopt");
}
std::unique_ptr<Formulation> MakeIpoptMpcc(const FormulationConfig&) {
  throw std::invalid_argument("ipopt-mpcc: this build has no Ipopt");
}

#else

bool IpoptAvailable() { return true; }

namespace {

using Ipopt::Index;
using Ipopt::Number;

// Options shared by both formulations (defaults and reasons in the comment block above).
struct IpoptCommonOptions {
  double tol = 1e-12;
  double constr_viol_tol = 1e-10;
  double compl_inf_tol = 1e-10;
  int max_iter = 300;
  std::string mu_strategy = "monotone";
  double warm_push = 1e-9;
  double warm_mu_init = 1e-6;

  void Read(OptionReader* reader) {
    tol = reader->GetReal("tol", tol);
    constr_viol_tol = reader->GetReal("constr_viol_tol", constr_viol_tol);
    compl_inf_tol = reader->GetReal("compl_inf_tol", compl_inf_tol);
    max_iter = reader->GetInteger("max_iter", max_iter);
    mu_strategy = reader->GetChoice("mu_strategy", mu_strategy, {"monotone", "adaptive"});
    warm_push = reader->GetReal("warm_push", warm_push);
    warm_mu_init = reader->GetReal("warm_mu_init", warm_mu_init);
  }
  void Check(const std::string& name) const {
    auto positive = [&](double v, const char* key) {
      if (!(v > 0.0)) throw std::invalid_argument(name + " option '" + key + "' must be > 0");
    };
    positive(tol, "tol");
    positive(constr_viol_tol, "constr_viol_tol");
    positive(compl_inf_tol, "compl_inf_tol");
    positive(warm_push, "warm_push");
    positive(warm_mu_init, "warm_mu_init");
    if (warm_push >= 0.5) throw std::invalid_argument(name + " option 'warm_push' must be < 0.5");
    if (max_iter < 0) throw std::invalid_argument(name + " option 'max_iter' must be >= 0");
  }
  std::string Settings() const {
    std::ostringstream out;
    out << "tol=" << tol << ";constr_viol_tol=" << constr_viol_tol
        << ";compl_inf_tol=" << compl_inf_tol << ";max_iter=" << max_iter
        << ";mu_strategy=" << mu_strategy << ";bound_relax_factor=0;nlp_scaling_method=none"
        << ";warm_push=" << warm_push << ";warm_mu_init=" << warm_mu_init;
    return out.str();
  }
};

const char* StatusName(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
      return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected:
      return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates:
      return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop:
      return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found:
      return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed:
      return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation:
      return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option:
      return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected:
      return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception:
      return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory:
      return "Insufficient_Memory";
    case Ipopt::Internal_Error:
      return "Internal_Error";
  }
  return "unknown";
}

Status MapStatus(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
      return Status::kConverged;
    case Ipopt::Maximum_Iterations_Exceeded:
    case Ipopt::Maximum_CpuTime_Exceeded:
      return Status::kLimitReached;
    case Ipopt::User_Requested_Stop:
      return Status::kStoppedByCaller;
    default:
      return Status::kFailed;
  }
}

// A primal-dual point of an IpoptNlp (what a warm start gives Ipopt and what it returns).
struct PrimalDual {
  Vec x, z_lower, z_upper, y;
  bool has_duals = false;
};

// What ipopt-energy / ipopt-mpcc leave in StepResult::warm_state for the next step's warm
// start: the final primal-dual point of the NLP, in its own scaled variables.
struct IpoptWarmState {
  std::string formulation;  // "ipopt-energy" or "ipopt-mpcc:<reformulation>"
  ConstraintKind kind = ConstraintKind::kArcLength;
  PrimalDual point;
};

// The TNLP over an IpoptNlp. Exceptions never leave these methods into Ipopt (ARCHITECTURE.md
// habit 2): they are caught, stored, the evaluation reports failure and the next
// intermediate_callback stops Ipopt; the caller rethrows after OptimizeTNLP returns.
class TnlpAdapter final : public Ipopt::TNLP {
 public:
  TnlpAdapter(IpoptNlp* nlp, const SolveControls& controls, const Stopwatch& clock,
              StepResult* result)
      : nlp_(*nlp), controls_(controls), clock_(clock), result_(*result) {}

  void set_start(const PrimalDual& start) {
    start_ = start;
    finalized_ = false;
  }
  const PrimalDual& solution() const { return solution_; }
  bool finalized() const { return finalized_; }
  std::exception_ptr error() const { return error_; }
  void set_iteration_offset(int offset) { iteration_offset_ = offset; }
  bool stopped_by_caller() const { return stopped_by_caller_; }
  double last_inf_pr() const { return last_inf_pr_; }
  double last_inf_du() const { return last_inf_du_; }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = nlp_.num_variables();
    m = nlp_.num_constraints();
    nnz_jac_g = static_cast<Index>(nlp_.jacobian_rows().size());
    nnz_h_lag = static_cast<Index>(nlp_.hessian_rows().size());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    std::copy_n(nlp_.x_lower().data(), n, x_l);
    std::copy_n(nlp_.x_upper().data(), n, x_u);
    std::copy_n(nlp_.c_lower().data(), m, g_l);
    std::copy_n(nlp_.c_upper().data(), m, g_u);
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_L, Number* z_U,
                          Index m, bool init_lambda, Number* lambda) override {
    if (init_x) std::copy_n(start_.x.data(), n, x);
    if ((init_z || init_lambda) && !start_.has_duals) return false;
    if (init_z) {
      std::copy_n(start_.z_lower.data(), n, z_L);
      std::copy_n(start_.z_upper.data(), n, z_U);
    }
    if (init_lambda) std::copy_n(start_.y.data(), m, lambda);
    return true;
  }

  bool eval_f(Index n, const Number* x, bool, Number& obj_value) override {
    return Guard([&] {
      ++result_.counts.residual_evals;
      return nlp_.Objective(Eigen::Map<const Vec>(x, n), &obj_value);
    });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    return Guard([&] {
      if (!nlp_.Gradient(Eigen::Map<const Vec>(x, n), &work_)) return false;
      std::copy_n(work_.data(), n, grad_f);
      return true;
    });
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    return Guard([&] {
      ++result_.counts.residual_evals;
      if (!nlp_.Constraints(Eigen::Map<const Vec>(x, n), &work_)) return false;
      std::copy_n(work_.data(), m, g);
      return true;
    });
  }

  bool eval_jac_g(Index n, const Number* x, bool, Index, Index nele_jac, Index* iRow, Index* jCol,
                  Number* values) override {
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

  bool eval_h(Index n, const Number* x, bool, Number obj_factor, Index m, const Number* lambda,
              bool, Index nele_hess, Index* iRow, Index* jCol, Number* values) override {
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

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number* z_L,
                         const Number* z_U, Index m, const Number*, const Number* lambda, Number,
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
  bool intermediate_callback(Ipopt::AlgorithmMode, Index iter, Number obj_value, Number inf_pr,
                             Number inf_du, Number, Number, Number, Number, Number alpha_pr, Index,
                             const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
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
      if ((controls_.interrupted && controls_.interrupted()) ||
          (controls_.time_limit_s > 0.0 && clock_.Seconds() > controls_.time_limit_s)) {
        stopped_by_caller_ = true;
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
  PrimalDual start_;
  PrimalDual solution_;
  bool finalized_ = false;
  bool stopped_by_caller_ = false;
  int iteration_offset_ = 0;
  double last_inf_pr_ = 0.0, last_inf_du_ = 0.0;
  std::exception_ptr error_;
  Vec work_;
};

Ipopt::SmartPtr<Ipopt::IpoptApplication> MakeApplication(const IpoptCommonOptions& o,
                                                         const SolveControls& controls) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication(false);
  Ipopt::OptionsList& options = *app->Options();
  options.SetIntegerValue("print_level", 0);
  options.SetStringValue("sb", "yes");
  options.SetNumericValue("tol", o.tol);
  options.SetNumericValue("constr_viol_tol", o.constr_viol_tol);
  options.SetNumericValue("compl_inf_tol", o.compl_inf_tol);
  options.SetIntegerValue("max_iter", o.max_iter);
  options.SetStringValue("mu_strategy", o.mu_strategy);
  options.SetNumericValue("bound_relax_factor", 0.0);
  options.SetStringValue("honor_original_bounds", "yes");
  options.SetStringValue("nlp_scaling_method", "none");
  if (controls.time_limit_s > 0.0) options.SetNumericValue("max_cpu_time", controls.time_limit_s);
  return app;
}

void SetWarmStartOptions(const IpoptCommonOptions& o, double mu_init,
                         Ipopt::IpoptApplication* app) {
  Ipopt::OptionsList& options = *app->Options();
  options.SetStringValue("warm_start_init_point", "yes");
  options.SetNumericValue("warm_start_bound_push", o.warm_push);
  options.SetNumericValue("warm_start_bound_frac", o.warm_push);
  options.SetNumericValue("warm_start_slack_bound_push", o.warm_push);
  options.SetNumericValue("warm_start_slack_bound_frac", o.warm_push);
  options.SetNumericValue("warm_start_mult_bound_push", o.warm_push);
  options.SetNumericValue("mu_init", mu_init);
}

// Runs Ipopt once; rethrows what a callback caught. Returns the raw status. The adapter is
// reference counted (Ipopt's SmartPtr), so the application may keep it as long as it likes.
Ipopt::ApplicationReturnStatus RunIpopt(Ipopt::IpoptApplication* app,
                                        const Ipopt::SmartPtr<TnlpAdapter>& adapter,
                                        StepResult* result) {
  Ipopt::SmartPtr<Ipopt::TNLP> tnlp = Ipopt::GetRawPtr(adapter);
  Ipopt::ApplicationReturnStatus status = app->Initialize(std::string());
  if (status == Ipopt::Solve_Succeeded) status = app->OptimizeTNLP(tnlp);
  if (adapter->error()) std::rethrow_exception(adapter->error());
  if (Ipopt::IsValid(app->Statistics())) {
    result->counts.iterations += app->Statistics()->IterationCount();
  }
  return status;
}

void RecordStatus(Ipopt::ApplicationReturnStatus status, const TnlpAdapter& adapter,
                  StepResult* result) {
  result->status = adapter.stopped_by_caller() ? Status::kStoppedByCaller : MapStatus(status);
  result->details["ipopt_status"] =
      std::to_string(static_cast<int>(status)) + " " + StatusName(status);
  result->details["ipopt_final_inf_pr"] = std::to_string(adapter.last_inf_pr());
  result->details["ipopt_final_inf_du"] = std::to_string(adapter.last_inf_du());
  result->details["linear_solves"] = "Hessian evaluations (one KKT factorisation each)";
  result->message = std::string("Ipopt: ") + StatusName(status);
}

const IpoptWarmState* PreviousState(const StartPoint& start, const std::string& formulation, int n,
                                    int m) {
  const IpoptWarmState* state = std::any_cast<IpoptWarmState>(&start.warm_state);
  if (state == nullptr || state->formulation != formulation || !state->point.has_duals ||
      state->point.x.size() != n || state->point.y.size() != m) {
    return nullptr;
  }
  return state;
}

// Makes (du, dlambda) satisfy the step constraint where that is a matter of the increment
// alone (as the implicit-FB warm start does): scaled onto the arc, or the prescribed load or
// displacement.
void FitIncrement(const StepProblem& step, Vec* du, double* dlambda) {
  const StepConstraint& c = step.constraint;
  switch (c.kind) {
    case ConstraintKind::kArcLength: {
      const double w = c.lambda_weight;
      const double norm = std::sqrt(du->squaredNorm() + w * w * (*dlambda) * (*dlambda));
      if (norm > 0.0) {
        *du *= c.arc_length / norm;
        *dlambda *= c.arc_length / norm;
      } else if (w > 0.0) {
        *dlambda = c.arc_length / w;
      }
      break;
    }
    case ConstraintKind::kFixedLoad:
      *dlambda = c.target - step.base.lambda;
      break;
    case ConstraintKind::kDisplacement:
      (*du)[c.index] = c.target - step.base.u[c.index];
      break;
    case ConstraintKind::kKink:
      break;
  }
}

// --- ipopt-energy --------------------------------------------------------------------------

class IpoptEnergy final : public Formulation {
 public:
  explicit IpoptEnergy(IpoptCommonOptions options) : options_(std::move(options)) {
    options_.Check(name());
  }
  std::string name() const override { return "ipopt-energy"; }
  std::string solver() const override { return "ipopt"; }
  std::string settings() const override { return options_.Settings(); }
  bool Supports(ConstraintKind kind) const override { return kind == ConstraintKind::kFixedLoad; }

 private:
  // Cold: du = 0 and Ipopt's own multiplier initialisation. Warm: du = start.du (rescaled),
  // the previous step's multipliers when the backend state is an energy one of the same size,
  // else y = -r^k / R (the reactions of the known state, clipped at 0), warm-start options on.
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    EnergyNlp nlp(step);  // throws std::invalid_argument for a model without energy
    const double length = step.scales.length;
    const double force = step.scales.force;
    const int d = step.num_dofs();
    const int nc = step.num_pairs();
    Stopwatch clock;
    auto app = MakeApplication(options_, controls);
    Ipopt::SmartPtr<TnlpAdapter> adapter = new TnlpAdapter(&nlp, controls, clock, result);
    PrimalDual x0;
    x0.x = Vec::Zero(d);
    if (start.kind == StartKind::kWarm) {
      x0.x = start.du / length;
      x0.z_lower = Vec::Zero(d);
      x0.z_upper = Vec::Zero(d);
      if (const IpoptWarmState* prev = PreviousState(start, name(), d, nc)) {
        x0.y = prev->point.y;
      } else {
        x0.y = (-start.r / force).cwiseMax(0.0);
      }
      x0.has_duals = true;
      SetWarmStartOptions(options_, options_.warm_mu_init, Ipopt::GetRawPtr(app));
    }
    adapter->set_start(x0);
    const Ipopt::ApplicationReturnStatus status = RunIpopt(Ipopt::GetRawPtr(app), adapter, result);
    RecordStatus(status, *adapter, result);

    const Vec x = adapter->finalized() ? adapter->solution().x : x0.x;
    result->point.du = length * x;
    Vec phi;
    step.model->Gaps(step.base.u + result->point.du, &phi);
    result->point.g = -phi;
    // KKT: (grad pi - lambda f)/R + grad phi^T y = 0 with y >= 0 (Ipopt's multiplier of
    // phi/L <= 0), i.e. (9) with r = -R y <= 0.
    result->point.r = adapter->finalized() ? Vec(-force * adapter->solution().y) : Vec::Zero(nc);
    result->point.dlambda = step.constraint.target - step.base.lambda;
    if (adapter->finalized()) {
      result->warm_state = IpoptWarmState{name(), step.constraint.kind, adapter->solution()};
    }
  }

  IpoptCommonOptions options_;
};

// --- ipopt-mpcc ----------------------------------------------------------------------------

struct MpccOptions {
  MpccReformulation reformulation = MpccReformulation::kPenalty;
  double penalty_weight = 1.0;
  double penalty_max_weight = 100.0;
  double scholtes_t0 = 1.0;
  double scholtes_factor = 0.1;
  double scholtes_t_min = 1e-12;
  double scholtes_warm_t0 = 1e-6;
  double scholtes_mu_init = 1e-9;
  double scholtes_inner_tol = 0.1;
};

class IpoptMpcc final : public Formulation {
 public:
  IpoptMpcc(IpoptCommonOptions common, const MpccOptions& options)
      : common_(std::move(common)), options_(options) {
    common_.Check(name());
    auto bad = [&](const std::string& why) {
      throw std::invalid_argument("ipopt-mpcc option " + why);
    };
    if (!(options_.penalty_weight > 0.0)) bad("'penalty_weight' must be > 0");
    if (!(options_.penalty_max_weight >= options_.penalty_weight)) {
      bad("'penalty_max_weight' must be >= penalty_weight");
    }
    if (!(options_.scholtes_t0 > 0.0)) bad("'scholtes_t0' must be > 0");
    if (!(options_.scholtes_factor > 0.0 && options_.scholtes_factor < 1.0)) {
      bad("'scholtes_factor' must be in (0, 1)");
    }
    if (!(options_.scholtes_t_min > 0.0)) bad("'scholtes_t_min' must be > 0");
    if (!(options_.scholtes_warm_t0 > 0.0)) bad("'scholtes_warm_t0' must be > 0");
    if (!(options_.scholtes_mu_init > 0.0)) bad("'scholtes_mu_init' must be > 0");
    if (!(options_.scholtes_inner_tol >= 0.0)) bad("'scholtes_inner_tol' must be >= 0");
  }
  std::string name() const override { return "ipopt-mpcc"; }
  std::string solver() const override { return "ipopt"; }
  std::string settings() const override {
    std::ostringstream out;
    out << "reformulation=" << ToString(options_.reformulation);
    if (options_.reformulation == MpccReformulation::kPenalty) {
      out << ";penalty_weight=" << options_.penalty_weight
          << ";penalty_max_weight=" << options_.penalty_max_weight;
    } else {
      out << ";scholtes_t0=" << options_.scholtes_t0
          << ";scholtes_warm_t0=" << options_.scholtes_warm_t0
          << ";scholtes_factor=" << options_.scholtes_factor
          << ";scholtes_t_min=" << options_.scholtes_t_min
          << ";scholtes_mu_init=" << options_.scholtes_mu_init
          << ";scholtes_inner_tol=" << options_.scholtes_inner_tol;
    }
    out << ";" << common_.Settings();
    return out.str();
  }
  bool Supports(ConstraintKind) const override { return true; }

 private:
  std::string StateName() const { return name() + ":" + ToString(options_.reformulation); }

  // Cold: du = 0, dlambda fitted to the step constraint, g^ = 1, r^ = -1 (the report's fixed
  //   start g^ = -1, r^ = +1 reflected into the bounds g^ >= 0, r^ <= 0, where an interior point
  //   method must start; the projection (0, 0) would sit on both bounds), Ipopt's own duals.
  // Warm: (38)-(41): du0, dlambda0 = the predicted increment fitted to the constraint,
  //   r^0 = r^k / R, g^0 = -phi(u^k + du0) / L (Ipopt pushes it inside its bounds by warm_push);
  //   duals = the previous step's final multipliers (warm_state) when they are of this
  //   formulation and size, else y = 0 and bound multipliers z_g = -w r^0, z_r = w g^0 (the
  //   penalty's exact duals at a complementary point), floored by warm_push.
  PrimalDual MakeStart(const StepProblem& step, const StartPoint& start, const MpccNlp& nlp,
                       double penalty_weight) const {
    const int d = step.num_dofs();
    const int nc = step.num_pairs();
    const double length = step.scales.length;
    const double force = step.scales.force;
    PrimalDual x0;
    x0.x = Vec::Zero(nlp.num_variables());
    Vec du = Vec::Zero(d);
    double dlambda = 0.0;
    if (start.kind == StartKind::kWarm) {
      du = start.du;
      dlambda = start.dlambda;
      FitIncrement(step, &du, &dlambda);
      Vec phi;
      step.model->Gaps(step.base.u + du, &phi);
      x0.x.segment(nlp.ix_g(), nc) = (-phi / length).cwiseMax(0.0);
      x0.x.segment(nlp.ix_r(), nc) = (start.r / force).cwiseMin(0.0);
    } else {
      FitIncrement(step, &du, &dlambda);
      x0.x.segment(nlp.ix_g(), nc).setConstant(1.0);
      x0.x.segment(nlp.ix_r(), nc).setConstant(-1.0);
    }
    x0.x.segment(nlp.ix_u(), d) = du / length;
    x0.x[nlp.ix_dlambda()] = dlambda;
    // Respect fixed variables (the kink pair).
    x0.x = x0.x.cwiseMax(nlp.x_lower()).cwiseMin(nlp.x_upper());
    if (start.kind == StartKind::kWarm) {
      if (const IpoptWarmState* prev =
              PreviousState(start, StateName(), nlp.num_variables(), nlp.num_constraints())) {
        x0.z_lower = prev->point.z_lower;
        x0.z_upper = prev->point.z_upper;
        x0.y = prev->point.y;
      } else {
        const double w =
            options_.reformulation == MpccReformulation::kPenalty ? penalty_weight : 0.0;
        x0.z_lower = Vec::Zero(nlp.num_variables());
        x0.z_upper = Vec::Zero(nlp.num_variables());
        x0.z_lower.segment(nlp.ix_g(), nc) = -w * x0.x.segment(nlp.ix_r(), nc);
        x0.z_upper.segment(nlp.ix_r(), nc) = w * x0.x.segment(nlp.ix_g(), nc);
        x0.y = Vec::Zero(nlp.num_constraints());
      }
      x0.has_duals = true;
    }
    return x0;
  }

  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    MpccNlp nlp(step, options_.reformulation, options_.penalty_weight);
    const int d = step.num_dofs();
    const int nc = step.num_pairs();
    Stopwatch clock;
    Ipopt::SmartPtr<TnlpAdapter> adapter = new TnlpAdapter(&nlp, controls, clock, result);
    PrimalDual x0 = MakeStart(step, start, nlp, options_.penalty_weight);
    const bool warm = start.kind == StartKind::kWarm;

    Ipopt::ApplicationReturnStatus status = Ipopt::Solve_Succeeded;
    PrimalDual last = x0;
    bool have_solution = false;
    if (options_.reformulation == MpccReformulation::kPenalty) {
      // An exact penalty is exact only above a threshold weight (the MPCC multipliers'): when
      // Ipopt does not converge (e.g. stalls at a local minimiser with positive penalty, as on
      // the degenerate Kojima-Shindo solution at weight 1), the step is solved again from the
      // same start with 10 times the weight, up to penalty_max_weight.
      double weight = options_.penalty_weight;
      int solves = 0;
      for (;;) {
        nlp.set_penalty_weight(weight);
        if (solves > 0) x0 = MakeStart(step, start, nlp, weight);
        auto app = MakeApplication(common_, controls);
        if (warm) SetWarmStartOptions(common_, common_.warm_mu_init, Ipopt::GetRawPtr(app));
        adapter->set_start(x0);
        adapter->set_iteration_offset(result->counts.iterations);
        status = RunIpopt(Ipopt::GetRawPtr(app), adapter, result);
        ++solves;
        if (adapter->finalized()) {
          last = adapter->solution();
          have_solution = true;
        }
        if (MapStatus(status) == Status::kConverged || adapter->stopped_by_caller()) break;
        if (weight * 10.0 > options_.penalty_max_weight * (1.0 + 1e-12)) break;
        weight *= 10.0;
      }
      result->details["penalty_solves"] = std::to_string(solves);
      result->details["penalty_final_weight"] = std::to_string(weight);
    } else {
      // Scholtes: t = t0, t0 q, t0 q^2, ... down to t_min (the last one solved at t_min), each
      // subproblem warm started from the previous one's primal-dual point. A warm step starts
      // at scholtes_warm_t0: its start is already nearly complementary, and a large t would
      // first pull it to the relaxed set's centre.
      double t = warm ? options_.scholtes_warm_t0 : options_.scholtes_t0;
      t = std::max(t, options_.scholtes_t_min);
      int subproblems = 0;
      bool warm_next = warm;
      PrimalDual current = x0;
      for (;;) {
        nlp.set_relaxation(t);
        IpoptCommonOptions subproblem = common_;
        if (t > options_.scholtes_t_min) {
          // An intermediate subproblem only feeds the next one: solved to scholtes_inner_tol
          // times t, which is all the accuracy its relaxed answer has for the MPCC anyway.
          const double loose = options_.scholtes_inner_tol * t;
          subproblem.tol = std::max(subproblem.tol, loose);
          subproblem.constr_viol_tol = std::max(subproblem.constr_viol_tol, loose);
          subproblem.compl_inf_tol = std::max(subproblem.compl_inf_tol, loose);
        }
        auto app = MakeApplication(subproblem, controls);
        // The first subproblem of a warm step starts from the previous step (warm_mu_init);
        // later ones from the previous subproblem's answer, closer still (scholtes_mu_init).
        if (warm_next) {
          SetWarmStartOptions(common_,
                              subproblems == 0 ? common_.warm_mu_init : options_.scholtes_mu_init,
                              Ipopt::GetRawPtr(app));
        }
        adapter->set_start(current);
        adapter->set_iteration_offset(result->counts.iterations);
        status = RunIpopt(Ipopt::GetRawPtr(app), adapter, result);
        ++subproblems;
        if (!adapter->finalized()) break;
        current = adapter->solution();
        last = current;
        have_solution = true;
        if (MapStatus(status) != Status::kConverged || adapter->stopped_by_caller()) break;
        if (t <= options_.scholtes_t_min) break;
        t = std::max(t * options_.scholtes_factor, options_.scholtes_t_min);
        warm_next = true;
      }
      result->details["scholtes_subproblems"] = std::to_string(subproblems);
      result->details["scholtes_final_t"] = std::to_string(t);
    }
    RecordStatus(status, *adapter, result);

    const double length = step.scales.length;
    const double force = step.scales.force;
    const Vec& x = last.x;
    result->point.du = length * x.segment(nlp.ix_u(), d);
    result->point.g = length * x.segment(nlp.ix_g(), nc);
    result->point.r = force * x.segment(nlp.ix_r(), nc);
    result->point.dlambda = x[nlp.ix_dlambda()];
    if (have_solution) {
      result->warm_state = IpoptWarmState{StateName(), step.constraint.kind, last};
    }
  }

  IpoptCommonOptions common_;
  MpccOptions options_;
};

}  // namespace

std::unique_ptr<Formulation> MakeIpoptEnergy(const FormulationConfig& config) {
  OptionReader reader("ipopt-energy", config.options);
  IpoptCommonOptions common;
  common.Read(&reader);
  reader.Finish();
  return std::make_unique<IpoptEnergy>(common);
}

std::unique_ptr<Formulation> MakeIpoptMpcc(const FormulationConfig& config) {
  OptionReader reader("ipopt-mpcc", config.options);
  IpoptCommonOptions common;
  common.Read(&reader);
  MpccOptions options;
  const std::string reformulation =
      reader.GetChoice("reformulation", "penalty", {"penalty", "scholtes"});
  options.reformulation =
      reformulation == "penalty" ? MpccReformulation::kPenalty : MpccReformulation::kScholtes;
  options.penalty_weight = reader.GetReal("penalty_weight", options.penalty_weight);
  options.penalty_max_weight = reader.GetReal("penalty_max_weight", options.penalty_max_weight);
  options.scholtes_t0 = reader.GetReal("scholtes_t0", options.scholtes_t0);
  options.scholtes_warm_t0 = reader.GetReal("scholtes_warm_t0", options.scholtes_warm_t0);
  options.scholtes_factor = reader.GetReal("scholtes_factor", options.scholtes_factor);
  options.scholtes_t_min = reader.GetReal("scholtes_t_min", options.scholtes_t_min);
  options.scholtes_mu_init = reader.GetReal("scholtes_mu_init", options.scholtes_mu_init);
  options.scholtes_inner_tol = reader.GetReal("scholtes_inner_tol", options.scholtes_inner_tol);
  reader.Finish();
  return std::make_unique<IpoptMpcc>(common, options);
}

#endif  // CONTACTBENCH_HAVE_IPOPT

}  // namespace cb
