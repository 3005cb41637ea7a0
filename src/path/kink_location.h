// Kink location (docs/method.md section 6): where a pair's contact status changes between two
// accepted states, the path has a nonsmooth point with g_p = r_p = 0, found by solving
// (29)-(32) with (53) in place of the arc-length row.
#pragma once

#include <optional>

#include "path/arc_length_norm.h"
#include "path/path.h"

namespace cb {

// The kinks located within one accepted step.
struct KinksOfStep {
  int found = 0;                 // verified and on the path between the two states
  int not_located = 0;           // solved for, but not verified or not between them
  std::optional<State> nearest;  // of those, the nearest to the state after the step
};

class KinkLocator {
 public:
  KinkLocator(const ContactModel& model, const ContactScales& scales, Formulation& formulation,
              const PathOptions& options);

  // Solves (53) for every pair whose status differs between accepted states a and b (the step
  // `step` from a to b), reporting each through observer.OnKink.
  // A pair `on_kink` >= 0 is skipped: a is its kink (a step onto a kink ahead; kink_ahead.h).
  KinksOfStep Locate(int step, const State& a, const State& b, PathObserver& observer,
                     int on_kink = -1) const;

  // Solves (53) for pair p from accepted state `from`, predicted by the increment `predicted`
  // and the reactions `r0`; `between` is left false for the caller to judge.
  KinkRecord SolveFrom(int step, int p, const State& from, const Increment& predicted,
                       const Vec& r0) const;

 private:
  KinkRecord Solve(int step, int p, const State& from, const State& to, double t) const;

  const ContactModel& model_;
  const ContactScales& scales_;
  Formulation& formulation_;
  const PathOptions& options_;
};

}  // namespace cb
