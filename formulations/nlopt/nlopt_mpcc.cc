// nlopt-mpcc: LD_SLSQP on the step NLP in penalty form (NloptMpccProblem). Start: warm, the
// implicit formulation's warm start (38)-(41) with g^, r^ moved bound_push inside the bounds;
// cold, du0 = 0, dlambda0 fitted to the step constraint, g^ = 1, r^ = -1 (the report's cold
// magnitudes with the signs the bounds demand).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "formulations/implicit_fb/implicit_fb.h"
#include "formulations/nlopt/nlopt.h"
#include "formulations/nlopt/nlopt_adapter.h"
#include "formulations/nlopt/nlopt_options.h"
#include "formulations/nlopt/nlopt_problems.h"

namespace cb {

namespace {

struct MpccData {
  NloptRun* run;
  NloptMpccProblem* problem;
};

double MpccObjective(unsigned n, const double* z, double* grad, void* data) {
  auto& d = *static_cast<MpccData*>(data);
  return d.run->Objective(
      n, z, grad, [&](const Vec& at, Vec* gradient) { return d.problem->Objective(at, gradient); },
      [&](const Vec& at, double value) {
        d.run->Record(value, std::numeric_limits<double>::quiet_NaN(),
                      ComplementarityResidual(d.problem->layout(), at), at);
      });
}

void MpccEqualities(unsigned m, double* values, unsigned n, const double* z, double* grad,
                    void* data) {
  auto& d = *static_cast<MpccData*>(data);
  double violation = 0.0;
  d.run->Constraints(m, values, n, grad, NloptRun::ConstraintType::kEquality, &violation,
                     [&] { d.problem->Equalities(Eigen::Map<const Vec>(z, n), values, grad); });
}

class NloptMpcc final : public Formulation {
 public:
  explicit NloptMpcc(const NloptMpccOptions& options) : options_(options) {}
  std::string name() const override { return "nlopt-mpcc"; }
  std::string solver() const override { return "nlopt-slsqp"; }
  std::string settings() const override {
    std::ostringstream out;
    out << "algorithm=slsqp;weight=" << options_.weight << ";residual_tol=" << options_.residual_tol
        << ";maxeval=" << options_.maxeval << ";iterations=evaluations";
    return out.str();
  }

 private:
  // Any constraint kind, up to max_dense_size unknowns (LD_SLSQP is dense).
  bool DoAccepts(const StepProblem& step, std::string* why) const override {
    const int n = Unknowns(step).size();
    if (n <= options_.max_dense_size) return true;
    *why =
        DenseSlsqpRefusal(name(), "d + 2 nc + 1 = " + std::to_string(n), options_.max_dense_size);
    return false;
  }

  // The unknowns z = (du, g^, r^, dlambda) of NloptMpccProblem.
  static StepEquationLayout Unknowns(const StepProblem& step) {
    return {step.num_dofs(), step.num_pairs(), /*has_rho=*/false};
  }

  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    const StepEquationLayout layout = Unknowns(step);
    const int n = layout.size();
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
    MpccData data{&run, &problem};
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
    run.SetStops(options_.ftol_rel, options_.xtol_rel, options_.maxeval);
    std::vector<double> z(z0.data(), z0.data() + n);
    double value = run.Optimize(&z);

    result->point = problem.Point(Eigen::Map<const Vec>(z.data(), n));
    result->details["final_objective"] = FormatDetail(value);
  }

  NloptMpccOptions options_;
};

}  // namespace

std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig& config) {
  return std::make_unique<NloptMpcc>(ReadNloptMpccOptions(config));
}

}  // namespace cb
