// The watch on a path that stops making progress (docs/method.md section 10): a path whose
// steps are accepted but which goes nowhere is a failure, not a success. Two signs:
//  - crawling: the accepted steps' arc length stays far below the requested theta of (33) for
//    many consecutive steps (every step is cut back, and the doubling after each accepted step
//    never recovers);
//  - retracing: consecutive accepted increments point nearly opposite ways, so the path moves
//    back and forth over the same states. One sharp turn is a kink (the path may turn by more
//    than 90 degrees there); a run of them is not.
#pragma once

#include <optional>
#include <string>

#include "path/arc_length_norm.h"

namespace cb {

struct StagnationOptions {
  // An accepted step is slow when its theta is below this fraction of the requested one...
  double slow_fraction = 1e-3;
  // ...and the path stagnates after this many consecutive slow steps (0: never).
  int max_slow_steps = 10;
  // Two consecutive increments reverse when the cosine of their angle (in the H inner product
  // of (33)) is below this...
  double reversal_cosine = -0.9;
  // ...and the path retraces itself after this many consecutive reversals (0: never).
  int max_reversals = 3;

  bool IsValid(std::string* why) const;
};

class StagnationMonitor {
 public:
  // `requested_theta` is the nominal arc length, `w` the load parameter's weight in (33).
  StagnationMonitor(const StagnationOptions& options, double requested_theta, double w);

  // Takes the accepted step `step` of arc length `theta` and increment `taken`; returns why the
  // path stagnates when it does (then the path stops as failed), nothing otherwise.
  std::optional<std::string> Observe(int step, double theta, const Increment& taken);

 private:
  std::optional<std::string> Crawling(int step, double theta);
  std::optional<std::string> Retracing(int step, const Increment& taken);

  StagnationOptions options_;
  double requested_theta_;
  double w_;
  int slow_steps_ = 0;
  double largest_slow_theta_ = 0.0;
  int reversals_ = 0;
  std::optional<Increment> previous_;
};

}  // namespace cb
