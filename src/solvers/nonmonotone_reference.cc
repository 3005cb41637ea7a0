#include "solvers/nonmonotone_reference.h"

#include <algorithm>

namespace cb {

NonmonotoneReference::NonmonotoneReference(int window, double merit)
    : window_(window), recent_(1, merit) {}

double NonmonotoneReference::Reference(double merit) const {
  return nonmonotone_ ? *std::max_element(recent_.begin(), recent_.end()) : merit;
}

void NonmonotoneReference::Accept(double merit, double step) {
  recent_.push_back(merit);
  if (static_cast<int>(recent_.size()) > window_) recent_.erase(recent_.begin());
  damped_in_a_row_ = step < 1.0 ? damped_in_a_row_ + 1 : 0;
  nonmonotone_ = nonmonotone_ || damped_in_a_row_ >= kStallIterations;
}

}  // namespace cb
