// The path driver: traces a loading path by the arc-length method (docs/method.md sections 3-6)
// with any Formulation, judging every step by the verdict. It knows formulations only through
// the common interface, and observes through PathObserver (no I/O here).
#pragma once

#include <optional>
#include <string>

#include "model/contact_model.h"
#include "path/stagnation.h"
#include "step/formulation.h"
#include "verdict/verdict.h"

namespace cb {

// What the driver does about the stability of the path (stability.h): nothing; count the
// unstable modes at every accepted state and record limit points and (located) bifurcation
// points; or also switch onto the other branch at a bifurcation point along its null vector.
enum class BifurcationMode { kOff, kDetect, kSwitch };
const char* ToString(BifurcationMode mode);
// "off", "detect" or "switch"; false for anything else.
bool ParseBifurcationMode(const std::string& text, BifurcationMode* mode);

struct PathOptions {
  double arc_length = 0.1;     // theta of (33)
  double lambda_weight = 1.0;  // w of ||(du, dlambda)||_H
  int max_steps = 100;         // accepted steps to take
  double tolerance = 1e-8;     // verdict tolerance, in (0, kMaxVerdictTolerance] (section 7)
  StartKind start = StartKind::kWarm;
  // A step that fails the verdict (or turns back) is retried with theta halved, at most this
  // many times; then the path stops with Status::kFailed. After an accepted step theta grows
  // back by a factor 2 up to its nominal value.
  int max_cutbacks = 6;
  bool locate_kinks = true;  // solve (53) for each pair whose contact status changed
  BifurcationMode bifurcations = BifurcationMode::kOff;
  int max_branch_switches = 1;  // kSwitch: switch at the first this many bifurcation points
  // kSwitch: the bifurcation point is bracketed by bisection of the arc length until the
  // bracket is below this fraction of theta.
  double bifurcation_tolerance = 1e-6;
  // When an arc-length path that goes on being accepted stops making progress
  // (stagnation.h): then it ends as kFailed.
  StagnationOptions stagnation;
  SolveControls controls;  // per-step time limit and interrupt hook
  // Every solve is done this many times from the same start, for the spread of its time
  // (step_solve.h): the first answer is the one judged and kept.
  int solve_repeats = 1;

  bool IsValid(std::string* why) const;
  // Throws std::invalid_argument("path options: " + why) when not valid.
  void Validate() const;
};

// One solve of one step.
struct StepAttempt {
  int step = 0;     // 1-based index of the step being taken
  int attempt = 0;  // 0 first, then one per cut-back
  ConstraintKind kind = ConstraintKind::kArcLength;
  double arc_length = 0.0;  // theta used (arc-length steps)
  Vec predicted_du;         // the predicted increment the warm start was given
  double predicted_dlambda = 0.0;
  bool across_contact_change = false;  // the prediction was bent at a contact change
  StepResult result;
  Verdict verdict;
  bool reversed = false;  // the answer turned back on the path (the guard rejected it)
  bool accepted = false;
  State state;                // the state the attempt reached (base + increment)
  int n_contact = 0;          // pairs in contact at `state` (CountContacts)
  int kinks = 0;              // kinks located between the previous state and this one
  std::optional<State> kink;  // of those, the one nearest this state
  // Unstable modes at `state` (stability.h: negative eigenvalues of the stiffness on the
  // motions that keep the closed contacts closed; 0 = stable); -1 when not computed.
  int stability = -1;
  int branch = 0;              // 0 on the initial branch, +1 after each branch switch
  bool branch_switch = false;  // this step left a bifurcation point onto another branch
  // A step off a bifurcation point (kind kHyperplane): the point it left from and the unit
  // normal of its plane (n_lambda = 0), so that a replay can pose it again.
  std::optional<State> switch_origin;
  Vec plane_normal;
};

// A nonsmooth point of the path (docs/method.md section 6): where pair `pair` has g = r = 0,
// located by solving (29)-(32) with (53) from the accepted state before it.
struct KinkRecord {
  int step = 0;  // located between accepted steps step - 1 and step
  int pair = 0;
  StepResult result;
  Verdict verdict;
  bool between = false;  // the point lies on the path between the two bracketing steps
  State state;
};

// A critical point of the path, found between accepted steps step - 1 and step:
//  - kLimit: the load parameter turned (dlambda changed sign); a smooth one is located by
//    bisection on the sign of the tangent's load component (`state`, `verdict`, `located`),
//    else `state` is the accepted state where it turned; `nonsmooth` when a kink was located
//    in one of the two steps around it (the report's point B of P2, a limit point made by a
//    contact change), and then `state` is that kink;
//  - kBifurcation: the number of unstable modes changed within a step whose contact status
//    did not change, and the orientation of the path (the sign of the determinant of the
//    step's Jacobian with its arc-length row) changed there too: the path crossed another
//    branch. Located by bisection of the arc length (`state`, `verdict`); `mode` is the null
//    vector there;
//  - kStabilityChange: the number of unstable modes changed together with the contact status
//    (a nonsmooth critical point), or could not be located; recorded only.
struct CriticalPointRecord {
  enum class Kind { kLimit, kBifurcation, kStabilityChange };
  int step = 0;
  Kind kind = Kind::kLimit;
  bool nonsmooth = false;
  State state;
  bool located = false;  // kBifurcation: bracketed to bifurcation_tolerance; kLimit: located
  int bisections = 0;
  Verdict verdict;
  Vec mode;               // kBifurcation: the null vector (unit norm)
  bool switched = false;  // the path left this point onto the other branch
  std::string message;
};
const char* ToString(CriticalPointRecord::Kind kind);

class PathObserver {
 public:
  virtual ~PathObserver() = default;
  virtual void OnAttempt(const StepAttempt& /*attempt*/) {}
  virtual void OnKink(const KinkRecord& /*kink*/) {}
  virtual void OnCriticalPoint(const CriticalPointRecord& /*point*/) {}
};

struct PathSummary {
  Status status = Status::kNotRun;  // kConverged when every requested step was accepted
  std::string message;
  int accepted_steps = 0;
  int attempts = 0;
  int kinks = 0;
  // Kinks solved for (53) but not verified or not between their steps (kinks.csv says which):
  // the path then ends as kFailed, whatever its steps did.
  int kinks_not_located = 0;
  int limit_points = 0;
  int bifurcations = 0;
  int branch_switches = 0;
  State final_state;
};

// The tangent predictor of docs/method.md section 5: solves
//   [K_t  -G_c^T] [du]   [f]
//   [G_c    0   ] [dr] = [0],   K_t = hess pi - sum_p r_p hess phi_p,
// with G_c the gap-Jacobian rows of the pairs closed at `state` (g/L + r/R <= 0), and scales
// (du, 1) to ||(du, dlambda)||_H = theta with dlambda > 0. Returns false with *why when the
// bordered stiffness is singular.
bool TangentPredictor(const ContactModel& model, const ContactScales& scales, const State& state,
                      double theta, double lambda_weight, Vec* du, double* dlambda,
                      std::string* why);

// Traces max_steps arc-length steps from `initial` (ArcLengthTracer, arc_length_tracer.h).
PathSummary TraceArcLengthPath(const ContactModel& model, const ContactScales& scales,
                               const State& initial, Formulation& formulation,
                               const PathOptions& options, PathObserver* observer);

// One fixed-load step from `initial` to lambda (P1). Warm start: du0 = 0, r0 = initial.r, or,
// when `guess` is given, du0 = guess->u - initial.u and r0 = guess->r (a start near a known
// solution, as the report's section 5.1 does for eta case 3); cold start: the formulation's
// fixed start.
PathSummary SolveFixedLoad(const ContactModel& model, const ContactScales& scales,
                           const State& initial, double lambda, Formulation& formulation,
                           const PathOptions& options, PathObserver* observer,
                           const State* guess = nullptr);

// The unloaded state: u = 0, r = 0, lambda = 0.
State ZeroState(const ContactModel& model);

}  // namespace cb
