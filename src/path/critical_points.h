// The critical points of the path within one accepted step (stability.h):
//  - a limit point, where the load parameter turns;
//  - a change of the number of unstable modes: with a change of the contact status it is a
//    nonsmooth critical point (recorded only); else each change is bracketed by bisection of
//    the arc length and classified by the orientation of the path across it (a bifurcation
//    point where the orientation changes, else the limit point).
#pragma once

#include <vector>

#include "path/path.h"
#include "path/step_origin.h"

namespace cb {

class CriticalPointFinder {
 public:
  CriticalPointFinder(const ContactModel& model, const ContactScales& scales,
                      Formulation& formulation, const PathOptions& options);

  // The critical points of the accepted step `taken` (its state, increment, kinks and
  // unstable modes) from `origin`, in the order they are to be reported. With `may_switch` the
  // first bifurcation point whose null vector is found is marked `switched`: the next step is
  // to leave it along that vector.
  std::vector<CriticalPointRecord> Find(const StepOrigin& origin, const StepAttempt& taken,
                                        bool may_switch) const;

 private:
  // The far side of a bracketed change of the count: the first verified point past it, at arc
  // length t from the origin.
  struct PastTheChange {
    double t = 0.0;
    int modes = 0;
    State state;
  };

  // A smooth limit point is bracketed until the bracket is below this fraction of the chord:
  // lambda is stationary there, so its error is of the order of the bracket squared.
  static constexpr double kLimitPointTolerance = 1e-6;

  void PlaceAtTheKink(const StepOrigin& origin, const StepAttempt& taken,
                      CriticalPointRecord* limit) const;
  void LocateLimitPoint(const StepOrigin& origin, const StepAttempt& taken,
                        CriticalPointRecord* limit) const;
  bool ContactStatusChanged(const State& origin, const StepAttempt& taken) const;
  void LocateModeChanges(const StepOrigin& origin, const StepAttempt& taken, bool may_switch,
                         std::vector<CriticalPointRecord>* critical) const;
  PastTheChange BracketModeChange(const State& a, int modes_a, const State& b, int modes_b,
                                  double t_from, CriticalPointRecord* point) const;

  const ContactModel& model_;
  const ContactScales& scales_;
  Formulation& formulation_;
  const PathOptions& options_;
};

}  // namespace cb
