// ipopt-energy: a fixed-load step as energy minimisation subject to phi(u) <= 0 (EnergyNlp,
// ipopt_nlp.h), solved by Ipopt through ipopt_adapter.h.
#include <string>

#include "formulations/common/energy_step.h"
#include "formulations/ipopt/ipopt.h"
#include "formulations/ipopt/ipopt_adapter.h"

namespace cb {

namespace {

class IpoptEnergy final : public Formulation {
 public:
  explicit IpoptEnergy(IpoptCommonOptions options) : options_(std::move(options)) {
    options_.Check(name());
  }
  std::string name() const override { return "ipopt-energy"; }
  std::string solver() const override { return "ipopt"; }
  std::string settings() const override { return options_.Settings(); }

 private:
  // A fixed-load step of a model with an energy (common/energy_step.h).
  bool DoAccepts(const StepProblem& step, std::string* why) const override {
    return IsEnergyStep(name(), step, why);
  }

  // Cold: du = 0 and Ipopt's own multiplier initialisation. Warm: du = start.du (rescaled),
  // the previous step's multipliers when the backend state is an energy one of the same size,
  // else y = -r^k / R (the reactions of the known state, clipped at 0), warm-start options on.
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    EnergyNlp nlp(step);
    const double length = step.scales.length;
    const double force = step.scales.force;
    const int d = step.num_dofs();
    const int nc = step.num_pairs();
    Stopwatch clock;
    auto app = MakeIpoptApplication(options_, controls);
    Ipopt::SmartPtr<TnlpAdapter> adapter = new TnlpAdapter(&nlp, controls, clock, result);
    IpoptPrimalDual x0;
    x0.x = Vec::Zero(d);
    if (start.kind == StartKind::kWarm) {
      x0.x = start.du / length;
      x0.z_lower = Vec::Zero(d);
      x0.z_upper = Vec::Zero(d);
      if (const IpoptWarmState* prev = PreviousIpoptState(start, name(), d, nc)) {
        x0.y = prev->point.y;
      } else {
        x0.y = (-start.r / force).cwiseMax(0.0);
      }
      x0.has_duals = true;
      SetIpoptWarmStartOptions(options_, options_.warm_mu_init, Ipopt::GetRawPtr(app));
    }
    adapter->set_start(x0);
    const Ipopt::ApplicationReturnStatus status = RunIpopt(Ipopt::GetRawPtr(app), adapter, result);
    RecordIpoptStatus(status, *adapter, result);

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

}  // namespace

std::unique_ptr<Formulation> MakeIpoptEnergy(const FormulationConfig& config) {
  OptionReader reader("ipopt-energy", config.options);
  IpoptCommonOptions common;
  common.Read(&reader);
  reader.Finish();
  return std::make_unique<IpoptEnergy>(common);
}

}  // namespace cb
