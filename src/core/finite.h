// A fast test that every value of an array is finite, for the checks done on each Jacobian and
// each matrix handed to a sparse solver (several thousand values per Newton iteration).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace cb {

// True when no value is NaN or +-Inf. Reads the exponent bits (all ones for NaN and Inf) with an
// integer OR-reduction, which the compiler vectorises; std::isfinite in an early-exit loop does
// not vectorise.
inline bool AllFinite(const double* values, std::size_t n) {
  constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;
  std::uint64_t any = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, values + i, sizeof(bits));
    any |= static_cast<std::uint64_t>((bits & kExponent) == kExponent);
  }
  return any == 0;
}

}  // namespace cb
