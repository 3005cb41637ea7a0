#include "path/stagnation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cb {

bool StagnationOptions::IsValid(std::string* why) const {
  if (!(slow_fraction > 0.0 && slow_fraction < 1.0)) {
    *why = "stagnation.slow_fraction must be in (0, 1)";
    return false;
  }
  if (!(reversal_cosine >= -1.0 && reversal_cosine < 0.0)) {
    *why = "stagnation.reversal_cosine must be in [-1, 0)";
    return false;
  }
  if (max_slow_steps < 0 || max_reversals < 0) {
    *why = "stagnation.max_slow_steps and max_reversals must be >= 0";
    return false;
  }
  return true;
}

StagnationMonitor::StagnationMonitor(const StagnationOptions& options, double requested_theta,
                                     double w)
    : options_(options), requested_theta_(requested_theta), w_(w) {}

std::optional<std::string> StagnationMonitor::Observe(int step, double theta,
                                                      const Increment& taken) {
  if (auto why = Crawling(step, theta)) return why;
  return Retracing(step, taken);
}

std::optional<std::string> StagnationMonitor::Crawling(int step, double theta) {
  if (options_.max_slow_steps == 0) return std::nullopt;
  if (!(theta < options_.slow_fraction * requested_theta_)) {
    slow_steps_ = 0;
    largest_slow_theta_ = 0.0;
    return std::nullopt;
  }
  ++slow_steps_;
  largest_slow_theta_ = std::max(largest_slow_theta_, theta);
  if (slow_steps_ < options_.max_slow_steps) return std::nullopt;
  std::ostringstream why;
  why << "the path stagnates: steps " << step - slow_steps_ + 1 << "-" << step
      << " were accepted with arc lengths of at most " << largest_slow_theta_ << ", below "
      << options_.slow_fraction << " of the requested " << requested_theta_;
  return why.str();
}

std::optional<std::string> StagnationMonitor::Retracing(int step, const Increment& taken) {
  if (options_.max_reversals == 0) return std::nullopt;
  const double norm = HNorm(taken.du, taken.dlambda, w_);
  bool reversed = false;
  if (previous_ && norm > 0.0) {
    const double previous_norm = HNorm(previous_->du, previous_->dlambda, w_);
    const double cosine = HInner(taken.du, taken.dlambda, previous_->du, previous_->dlambda, w_) /
                          (norm * previous_norm);
    reversed = previous_norm > 0.0 && cosine < options_.reversal_cosine;
  }
  previous_ = taken;
  reversals_ = reversed ? reversals_ + 1 : 0;
  if (reversals_ < options_.max_reversals) return std::nullopt;
  std::ostringstream why;
  why << "the path retraces itself: steps " << step - reversals_ << "-" << step
      << " moved back and forth (each increment reversed the one before it)";
  return why.str();
}

}  // namespace cb
