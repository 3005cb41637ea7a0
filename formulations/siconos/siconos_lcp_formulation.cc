// siconos-lemke, siconos-newton-fb, siconos-newton-min: a fixed-load step as the dense LCP of
// siconos_lcp.h, solved by one of Siconos's LCP solvers (siconos_adapter.h). The three differ
// only in the Siconos solver id, so they are one class here; they are three formulations (not
// one with a solver option) so that the records, the profiles and the tables of the comparison,
// which are grouped by formulation name, keep the three methods apart without a --set per run.
//
// Warm start: z^ from the start's point (SteppedLcp::ZFromPoint: the predicted increment for an
// LCP as it is, the reactions r^k of the known state after the elimination), given to Newton-FB
// and Newton-min as their first iterate. Lemke pivots from its own initial basis whatever z it
// is given, so its warm and cold solves are the same. Cold: z^ = 0.
//
// SolveControls: the interrupt hook and the time limit are checked before the call; Siconos's
// drivers have no callback between iterations, so a solve that runs past the limit cannot be
// stopped in the middle (a dense Lemke in particular) and is reported as Status::kTimeLimit
// when it returns, whatever it found, as every backend's late solve is.
#include <string>

#include "core/timer.h"
#include "formulations/siconos/siconos.h"
#include "formulations/siconos/siconos_adapter.h"
#include "formulations/siconos/siconos_lcp.h"
#include "step/time_limit.h"

namespace cb {

namespace {

class SiconosLcpFormulation final : public Formulation {
 public:
  SiconosLcpFormulation(std::string name, SiconosLcpSolver solver, SiconosLcpOptions options)
      : name_(std::move(name)), solver_(solver), options_(options) {
    options_.Check(name_);
  }
  std::string name() const override { return name_; }
  std::string solver() const override { return "siconos"; }
  std::string settings() const override { return options_.Settings(solver_); }

 private:
  bool DoAccepts(const StepProblem& step, std::string* why) const override {
    return SteppedLcp::CanReduce(name_, step, options_.max_size, why);
  }

  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    Stopwatch clock;
    const SteppedLcp lcp(step);
    result->details["lcp"] = SteppedLcp::KindName(lcp.kind());
    result->details["lcp_size"] = std::to_string(lcp.size());
    const Vec z0 =
        start.kind == StartKind::kWarm ? lcp.ZFromPoint(start.du, start.r) : Vec::Zero(lcp.size());
    if (!lcp.m().allFinite() || !lcp.q().allFinite()) {
      // Siconos's pivoting and LAPACK calls are not meant for NaN: a failed step, not a call.
      result->status = Status::kFailed;
      result->message =
          "the LCP has non-finite entries (the model's forces or gaps are not finite)";
      result->point = lcp.PointFromZ(Vec::Zero(lcp.size()));
      return;
    }
    if (StoppedBeforeTheCall(controls, clock, result)) {
      result->point = lcp.PointFromZ(z0);
      return;
    }
    const SiconosLcpOutcome outcome = RunSiconosLcp(solver_, options_, lcp.m(), lcp.q(), z0);
    RecordSiconosOutcome(solver_, outcome, result);
    result->point = lcp.PointFromZ(outcome.z);
    if (PastTimeLimit(controls, clock)) {
      result->status = Status::kTimeLimit;
      result->message += " (" + TimeLimitMessage(controls.time_limit_s) + ")";
    }
  }

  // The controls as far as they can act: before Siconos's call, which cannot be interrupted.
  static bool StoppedBeforeTheCall(const SolveControls& controls, const Stopwatch& clock,
                                   StepResult* result) {
    if (controls.interrupted && controls.interrupted()) {
      result->status = Status::kStoppedByCaller;
      result->message = "stopped by the caller before Siconos's call";
      return true;
    }
    if (PastTimeLimit(controls, clock)) {
      result->status = Status::kTimeLimit;
      result->message = TimeLimitMessage(controls.time_limit_s) + " before Siconos's call";
      return true;
    }
    return false;
  }

  std::string name_;
  SiconosLcpSolver solver_;
  SiconosLcpOptions options_;
};

std::unique_ptr<Formulation> MakeSiconosLcp(const std::string& name, SiconosLcpSolver solver,
                                            const FormulationConfig& config) {
  OptionReader reader(name, config.options);
  SiconosLcpOptions options;
  options.Read(&reader);
  reader.Finish();
  return std::make_unique<SiconosLcpFormulation>(name, solver, options);
}

}  // namespace

std::unique_ptr<Formulation> MakeSiconosLemke(const FormulationConfig& config) {
  return MakeSiconosLcp("siconos-lemke", SiconosLcpSolver::kLemke, config);
}

std::unique_ptr<Formulation> MakeSiconosNewtonFb(const FormulationConfig& config) {
  return MakeSiconosLcp("siconos-newton-fb", SiconosLcpSolver::kNewtonFb, config);
}

std::unique_ptr<Formulation> MakeSiconosNewtonMin(const FormulationConfig& config) {
  return MakeSiconosLcp("siconos-newton-min", SiconosLcpSolver::kNewtonMin, config);
}

}  // namespace cb
