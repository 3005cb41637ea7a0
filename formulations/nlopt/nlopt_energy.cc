// nlopt-energy: fixed-load steps of models with an energy: min pi(u) - lambda f^T u s.t.
// phi(u) <= 0 (NloptEnergyProblem for the scaling). A floor every energy method meets: near the
// optimum a step that reduces the residual e of (29) lowers the energy by only ~ e^2 / K, which
// vanishes below the energy's rounding (eps |pi|) long before e meets the verdict
// (docs/findings.md, "Known limitations", has where each algorithm stalls). Start: du0
// = start.du (warm; the path driver's fixed-load start is du = 0) or du0 = 0 (cold). Reactions by
// least squares from (29) on the active pairs (NloptEnergyProblem::Recover).
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "formulations/common/energy_step.h"
#include "formulations/nlopt/nlopt.h"
#include "formulations/nlopt/nlopt_adapter.h"
#include "formulations/nlopt/nlopt_options.h"
#include "formulations/nlopt/nlopt_problems.h"

namespace cb {

namespace {

struct EnergyData {
  NloptRun* run;
  const NloptEnergyProblem* problem;
  double constraint_tol;
  double value = HUGE_VAL;  // the objective at run->last_x()
  // The evaluated point of least objective whose violation max_p phi_p / L is within
  // constraint_tol (see NloptEnergy::DoSolve).
  Vec best_y;
  double best_value = HUGE_VAL;
};

double EnergyObjective(unsigned n, const double* y, double* grad, void* data) {
  auto& d = *static_cast<EnergyData*>(data);
  return d.run->Objective(
      n, y, grad, [&](const Vec& at, Vec* gradient) { return d.problem->Objective(at, gradient); },
      [&](const Vec& at, double value) {
        d.value = value;
        d.run->Record(value, std::numeric_limits<double>::quiet_NaN(),
                      std::numeric_limits<double>::quiet_NaN(), at);
      });
}

void EnergyConstraints(unsigned m, double* values, unsigned n, const double* y, double* grad,
                       void* data) {
  auto& d = *static_cast<EnergyData*>(data);
  double violation = 0.0;
  const bool done = d.run->Constraints(
      m, values, n, grad, NloptRun::ConstraintType::kInequality, &violation,
      [&] { d.problem->Constraints(Eigen::Map<const Vec>(y, n), values, grad); });
  const Vec& at = d.run->last_x();
  const bool same_point = at.size() == n && at == Eigen::Map<const Vec>(y, n);
  if (done && same_point && violation <= d.constraint_tol && d.value < d.best_value) {
    d.best_value = d.value;
    d.best_y = at;
  }
}

nlopt_algorithm EnergyAlgorithm(const std::string& name) {
  if (name == "ccsaq") return NLOPT_LD_CCSAQ;
  if (name == "slsqp") return NLOPT_LD_SLSQP;
  return NLOPT_LD_MMA;
}

class NloptEnergy final : public Formulation {
 public:
  explicit NloptEnergy(NloptEnergyOptions options) : options_(std::move(options)) {}
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

 private:
  // A fixed-load step of a model with an energy (common/energy_step.h), within the sizes of
  // max_dense_size (LD_SLSQP) and max_gradient_entries (NLopt's dense constraint gradient).
  bool DoAccepts(const StepProblem& step, std::string* why) const override {
    if (!IsEnergyStep(name(), step, why)) return false;
    const int d = step.num_dofs();
    const int nc = step.num_pairs();
    if (options_.algorithm == "slsqp" && d > options_.max_dense_size) {
      *why = DenseSlsqpRefusal(name(), std::to_string(d), options_.max_dense_size) +
             " (use algorithm=mma or ccsaq)";
      return false;
    }
    if (static_cast<double>(nc) * d > options_.max_gradient_entries) {
      *why = name() + ": NLopt's vector-valued constraint needs a dense " + std::to_string(nc) +
             " x " + std::to_string(d) + " gradient, above max_gradient_entries = " +
             FormatDetail(options_.max_gradient_entries);
      return false;
    }
    return true;
  }

  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    const NloptEnergyProblem problem(step);
    const int d = problem.size();
    const int nc = problem.num_constraints();
    // Warm: the increment the driver predicts (du = 0 for its fixed-load steps); cold: du = 0.
    Vec y0 = Vec::Zero(d);
    if (start.kind == StartKind::kWarm) y0 = start.du / step.scales.length;

    NloptRun run(EnergyAlgorithm(options_.algorithm), static_cast<unsigned>(d), controls, result);
    EnergyData data{&run, &problem, options_.constraint_tol, HUGE_VAL, Vec(), HUGE_VAL};
    nlopt_opt opt = run.opt();
    CheckSetup(nlopt_set_min_objective(opt, EnergyObjective, &data), "the objective");
    if (nc > 0) {
      const std::vector<double> tol(nc, options_.constraint_tol);
      CheckSetup(nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(nc), EnergyConstraints,
                                                  &data, tol.data()),
                 "the gap constraints");
    }
    run.SetStops(options_.ftol_rel, options_.xtol_rel, options_.maxeval);
    std::vector<double> y(y0.data(), y0.data() + d);
    double value = run.Optimize(&y);

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
            "best feasible evaluation (NLopt's point violates by " + FormatDetail(violation) + ")";
      }
    }
    int active = 0;
    result->point = problem.Recover(answer, options_.active_tol, &active);
    result->details["active_pairs"] = std::to_string(active);
    result->details["final_objective"] = FormatDetail(value);
    result->details["reactions"] = "least squares on the active pairs (NLopt has no multipliers)";
  }

  NloptEnergyOptions options_;
};

}  // namespace

std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig& config) {
  return std::make_unique<NloptEnergy>(ReadNloptEnergyOptions(config));
}

}  // namespace cb
