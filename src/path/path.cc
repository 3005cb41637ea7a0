#include "path/path.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "path/arc_length_tracer.h"
#include "path/stability.h"
#include "path/step_solve.h"

namespace cb {

bool PathOptions::IsValid(std::string* why) const {
  if (!(arc_length > 0.0) || !std::isfinite(arc_length)) {
    *why = "arc_length must be positive and finite";
    return false;
  }
  if (!(lambda_weight >= 0.0) || !std::isfinite(lambda_weight)) {
    *why = "lambda_weight must be >= 0 and finite";
    return false;
  }
  if (max_steps < 1) {
    *why = "max_steps must be >= 1";
    return false;
  }
  if (!(tolerance > 0.0) || !(tolerance <= kMaxVerdictTolerance)) {
    std::ostringstream range;
    range << "tolerance must be in (0, " << kMaxVerdictTolerance << "]";
    *why = range.str();
    return false;
  }
  if (max_cutbacks < 0) {
    *why = "max_cutbacks must be >= 0";
    return false;
  }
  if (solve_repeats < 1) {
    *why = "solve_repeats must be >= 1";
    return false;
  }
  return stagnation.IsValid(why);
}

void PathOptions::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw std::invalid_argument("path options: " + why);
}

State ZeroState(const ContactModel& model) {
  return {Vec::Zero(model.num_dofs()), Vec::Zero(model.num_pairs()), 0.0};
}

bool TangentPredictor(const ContactModel& model, const ContactScales& scales, const State& state,
                      double theta, double lambda_weight, Vec* du, double* dlambda,
                      std::string* why) {
  const BorderedStiffness stiffness(model, scales, state);
  if (!stiffness.SolveDisplacement(model.load_pattern(), du)) {
    *why = "tangent predictor: " +
           (stiffness.ok() ? std::string("the tangent is not finite") : stiffness.message());
    return false;
  }
  const double norm = std::sqrt(du->squaredNorm() + lambda_weight * lambda_weight);
  *du *= theta / norm;
  *dlambda = theta / norm;
  return true;
}

const char* ToString(BifurcationMode mode) {
  switch (mode) {
    case BifurcationMode::kOff:
      return "off";
    case BifurcationMode::kDetect:
      return "detect";
    case BifurcationMode::kSwitch:
      return "switch";
  }
  return "?";
}

bool ParseBifurcationMode(const std::string& text, BifurcationMode* mode) {
  for (BifurcationMode m :
       {BifurcationMode::kOff, BifurcationMode::kDetect, BifurcationMode::kSwitch}) {
    if (text == ToString(m)) {
      *mode = m;
      return true;
    }
  }
  return false;
}

const char* ToString(CriticalPointRecord::Kind kind) {
  switch (kind) {
    case CriticalPointRecord::Kind::kLimit:
      return "limit";
    case CriticalPointRecord::Kind::kBifurcation:
      return "bifurcation";
    case CriticalPointRecord::Kind::kStabilityChange:
      return "stability_change";
  }
  return "?";
}

PathSummary TraceArcLengthPath(const ContactModel& model, const ContactScales& scales,
                               const State& initial, Formulation& formulation,
                               const PathOptions& options, PathObserver* observer) {
  return ArcLengthTracer(model, scales, formulation, options, observer).Run(initial);
}

PathSummary SolveFixedLoad(const ContactModel& model, const ContactScales& scales,
                           const State& initial, double lambda, Formulation& formulation,
                           const PathOptions& options, PathObserver* observer, const State* guess) {
  options.Validate();
  StepProblem problem{&model, initial, StepConstraint::FixedLoad(lambda), scales};
  StartPoint start;
  start.kind = options.start;
  start.du = guess != nullptr ? Vec(guess->u - initial.u) : Vec(Vec::Zero(model.num_dofs()));
  start.dlambda = lambda - initial.lambda;
  start.r = guess != nullptr ? guess->r : initial.r;
  StepAttempt attempt;
  attempt.step = 1;
  attempt.kind = ConstraintKind::kFixedLoad;
  attempt.predicted_du = start.du;
  attempt.predicted_dlambda = start.dlambda;
  RecordJudgedStep(SolveAndJudge(formulation, problem, start, options), &attempt);
  attempt.accepted = SolvedAndVerified(attempt.result, attempt.verdict);
  if (observer != nullptr) observer->OnAttempt(attempt);

  PathSummary summary;
  summary.attempts = 1;
  summary.final_state = attempt.accepted ? attempt.state : initial;
  summary.accepted_steps = attempt.accepted ? 1 : 0;
  if (attempt.accepted) {
    summary.status = Status::kConverged;
    summary.message = "fixed-load step verified";
  } else {
    summary.status = attempt.result.status == Status::kStoppedByCaller ? Status::kStoppedByCaller
                                                                       : Status::kFailed;
    summary.message =
        "fixed-load step not verified (solver: " + std::string(ToString(attempt.result.status)) +
        ", " + attempt.result.message + ")";
  }
  return summary;
}

}  // namespace cb
