// A fast test that every value of an array is finite, for the checks done on each Jacobian and
// each matrix handed to a sparse solver (several thousand values per Newton iteration).
#pragma once

#include <cstddef>

namespace cb {

// True when no value is NaN or +-Inf. x * 0 is (+-)0 for every finite x and NaN for NaN and
// +-Inf, so the sum of the products is NaN exactly when some value is not finite. Four
// independent sums let the compiler use packed SSE2 arithmetic without reassociating (no
// -ffast-math), where an exponent-bit test does not vectorise on baseline x86-64 (no 64-bit
// integer compare before SSE4.1), nor std::isfinite in an early-exit loop. Two such checks run
// per Newton iteration (Jacobian, linear solver); docs/findings.md, "Performance", has the
// timings.
inline bool AllFinite(const double* values, std::size_t n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += values[i] * 0.0;
    s1 += values[i + 1] * 0.0;
    s2 += values[i + 2] * 0.0;
    s3 += values[i + 3] * 0.0;
  }
  for (; i < n; ++i) s0 += values[i] * 0.0;
  const double sum = (s0 + s1) + (s2 + s3);
  return sum == sum;  // false only for NaN
}

}  // namespace cb
