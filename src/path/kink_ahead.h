// A step onto a kink ahead (docs/method.md section 10, item 5): when every attempt of a step
// fails, the path may be running into a contact change it cannot step across, a kink where the
// load turns (the two-bar truss coming down onto its floor with the load at its minimum; P3's
// `howe` reading, where a contact opens onto an unstable piece). The pair whose switching
// function g/L + r/R runs to zero within the step is found by extrapolating it from the last
// two accepted states; the kink is solved for with (53) from the last state, as a step of its
// own, and the path leaves it along the tangent of the other piece: the bordered stiffness with
// that pair's status switched, signed so that the pair stays feasible (a closed pair's reaction
// grows in compression, an open pair's gap opens).
#pragma once

#include <optional>

#include "path/arc_length_norm.h"
#include "path/kink_location.h"
#include "path/path.h"

namespace cb {

struct KinkAhead {
  KinkRecord kink;  // verified, ahead of the state, within reach
  Increment leave;  // the direction of the other piece at the kink, unit in ||.||_H
};

class KinkAheadFinder {
 public:
  KinkAheadFinder(const ContactModel& model, const ContactScales& scales,
                  const KinkLocator& locator, const PathOptions& options);

  // From accepted state `at`, reached from `before`, heading along `heading`: the nearest kink
  // within `reach` (arc length) ahead, solved and verified, with the direction to leave it.
  std::optional<KinkAhead> Find(int step, const State& before, const State& at,
                                const Increment& heading, double reach) const;

 private:
  const ContactModel& model_;
  const ContactScales& scales_;
  const KinkLocator& locator_;
  const PathOptions& options_;
};

}  // namespace cb
