// The arc-length path driver (docs/method.md sections 3-6) behind TraceArcLengthPath. Each step of
// Run() is a sequence of named steps: choose how the step leaves its origin (a StepLeg: along
// the branch, or off a bifurcation point), attempt it with cut-backs of the arc length, locate
// the kinks within it and redirect the path past them, detect the critical points within it,
// accept it, and stop the path when it stagnates (stagnation.h).
#pragma once

#include <any>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "path/arc_length_norm.h"
#include "path/critical_points.h"
#include "path/kink_ahead.h"
#include "path/kink_location.h"
#include "path/path.h"
#include "path/stagnation.h"
#include "path/step_leg.h"
#include "path/step_origin.h"

namespace cb {

class ArcLengthTracer {
 public:
  // Throws std::invalid_argument naming the bad field of `options`. The arguments must outlive
  // the tracer; `observer` may be null.
  ArcLengthTracer(const ContactModel& model, const ContactScales& scales, Formulation& formulation,
                  const PathOptions& options, PathObserver* observer);

  // Traces options.max_steps accepted steps from `initial`.
  PathSummary Run(const State& initial);

 private:
  // How the attempts of one step ended.
  enum class Outcome { kAccepted, kRejected, kStoppedByCaller };

  // Where the path is: its last accepted state (the origin of the next step along the branch),
  // the direction it goes on in, and the branch it is on (0 initially, +1 per switch).
  // `behind`: the accepted states before it on its branch, nearest first, covering
  // at least twice the nominal arc length (the turn-back guard's trail, turn_back.h).
  struct Position {
    StepOrigin accepted;
    Increment heading;
    int branch = 0;
    std::deque<State> behind;
    bool behind_reaches_start = true;  // `behind` ends at the path's first state
    int on_kink = -1;  // the pair whose kink the state is, after a step onto a kink ahead
  };

  // How the next step is taken: its arc length, the backend state its warm start may reuse,
  // and the bifurcation point it is to leave from, if one was located for a switch.
  struct NextStep {
    double theta = 0.0;
    std::any warm_state;
    std::optional<CriticalPointRecord> branch_switch;
  };

  bool Start(const State& initial);
  std::unique_ptr<StepLeg> NextLeg() const;
  std::vector<Increment> Trail() const;
  void KeepBehind(const StepAttempt& attempt);
  // The kinks located within an accepted attempt, held until it is reported.
  struct LocatedKinks final : PathObserver {
    void OnKink(const KinkRecord& kink) override { records.push_back(kink); }
    KinksOfStep of_step;
    std::vector<KinkRecord> records;
  };

  Outcome AttemptWithCutbacks(int step, const StepLeg& leg, StepAttempt* attempt,
                              LocatedKinks* kinks);
  void ReportRejected(std::vector<StepAttempt> rejected, std::optional<StepAttempt> held);
  StepAttempt Attempt(int step, int index, const StepLeg& leg);
  std::optional<Increment> BentAtContactChange(const StepLeg& leg,
                                               const Increment& prediction) const;
  void AbandonBranchSwitch();
  bool StepOntoKinkAhead(int step, const StepLeg& leg, int attempts);
  void EnterNewBranch();
  LocatedKinks LocateKinks(const StepLeg& leg, const StepAttempt& attempt) const;
  void RecordKinksAndRedirect(const LocatedKinks& kinks, StepAttempt* attempt);
  std::vector<CriticalPointRecord> DetectCriticalPoints(const StepLeg& leg, StepAttempt* attempt);
  void Accept(const StepAttempt& attempt, const std::vector<CriticalPointRecord>& critical);
  std::string StepFailure(int step, const StepAttempt& last) const;
  bool InterruptedByCaller() const;
  PathSummary Finish(Status status, std::string message);

  const ContactModel& model_;
  const ContactScales& scales_;
  Formulation& formulation_;
  const PathOptions& options_;
  PathObserver no_observer_;
  PathObserver& observer_;
  const KinkLocator kink_locator_;
  const CriticalPointFinder critical_point_finder_;
  const KinkAheadFinder kink_ahead_finder_;

  // The kinks stepped onto so far (pair and state): a path that comes back to one cycles.
  std::vector<std::pair<int, State>> kinks_stepped_onto_;
  PathSummary summary_;
  StagnationMonitor stagnation_;
  Position at_;
  NextStep next_;
};

}  // namespace cb
