#include "formulations/ipopt/ipopt_adapter.h"

#include <IpoptConfig.h>

#include <IpSolveStatistics.hpp>
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "formulations/ipopt/ipopt.h"

namespace cb {

bool IpoptAvailable() { return true; }
std::string IpoptVersion() { return IPOPT_VERSION; }

void IpoptCommonOptions::Read(OptionReader* reader) {
  tol = reader->GetReal("tol", tol);
  constr_viol_tol = reader->GetReal("constr_viol_tol", constr_viol_tol);
  compl_inf_tol = reader->GetReal("compl_inf_tol", compl_inf_tol);
  max_iter = reader->GetInteger("max_iter", max_iter);
  mu_strategy = reader->GetChoice("mu_strategy", mu_strategy, {"monotone", "adaptive"});
  warm_push = reader->GetReal("warm_push", warm_push);
  warm_mu_init = reader->GetReal("warm_mu_init", warm_mu_init);
}

void IpoptCommonOptions::Check(const std::string& name) const {
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

std::string IpoptCommonOptions::Settings() const {
  std::ostringstream out;
  out << "tol=" << tol << ";constr_viol_tol=" << constr_viol_tol
      << ";compl_inf_tol=" << compl_inf_tol << ";max_iter=" << max_iter
      << ";mu_strategy=" << mu_strategy << ";bound_relax_factor=0;nlp_scaling_method=none"
      << ";warm_push=" << warm_push << ";warm_mu_init=" << warm_mu_init;
  return out.str();
}

const char* IpoptStatusName(Ipopt::ApplicationReturnStatus s) {
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

Status MapIpoptStatus(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
      return Status::kConverged;
    case Ipopt::Maximum_Iterations_Exceeded:
      return Status::kLimitReached;
    case Ipopt::Maximum_CpuTime_Exceeded:  // only set from SolveControls::time_limit_s
      return Status::kTimeLimit;
    case Ipopt::User_Requested_Stop:
      return Status::kStoppedByCaller;
    default:
      return Status::kFailed;
  }
}

Ipopt::SmartPtr<Ipopt::IpoptApplication> MakeIpoptApplication(const IpoptCommonOptions& o,
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

void SetIpoptWarmStartOptions(const IpoptCommonOptions& o, double mu_init,
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

void RecordIpoptStatus(Ipopt::ApplicationReturnStatus status, const TnlpAdapter& adapter,
                       StepResult* result) {
  result->status = MapIpoptStatus(status);
  if (adapter.stopped_by_controls()) {
    result->status = adapter.timed_out() ? Status::kTimeLimit : Status::kStoppedByCaller;
  }
  result->details["ipopt_status"] =
      std::to_string(static_cast<int>(status)) + " " + IpoptStatusName(status);
  result->details["ipopt_final_inf_pr"] = std::to_string(adapter.last_inf_pr());
  result->details["ipopt_final_inf_du"] = std::to_string(adapter.last_inf_du());
  result->details["linear_solves"] = "Hessian evaluations (one KKT factorisation each)";
  result->message = std::string("Ipopt: ") + IpoptStatusName(status);
  if (result->status == Status::kTimeLimit) {
    result->message += " (" + TimeLimitMessage(adapter.time_limit_s()) + ")";
  }
}

const IpoptWarmState* PreviousIpoptState(const StartPoint& start, const std::string& formulation,
                                         int n, int m) {
  const IpoptWarmState* state = std::any_cast<IpoptWarmState>(&start.warm_state);
  if (state == nullptr || state->formulation != formulation || !state->point.has_duals ||
      state->point.x.size() != n || state->point.y.size() != m) {
    return nullptr;
  }
  return state;
}

}  // namespace cb
