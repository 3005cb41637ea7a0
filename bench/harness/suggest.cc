#include "harness/suggest.h"

#include <algorithm>
#include <numeric>

namespace cb::harness {

std::size_t EditDistance(const std::string& a, const std::string& b) {
  // One row of the dynamic programme: row[j] = distance(a[0..i), b[0..j)).
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({above + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::optional<std::string> ClosestMatch(const std::string& typed,
                                        const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  std::vector<std::string> extensions;  // candidates `typed` is a prefix of
  for (const std::string& candidate : candidates) {
    if (!typed.empty() && candidate.rfind(typed, 0) == 0) extensions.push_back(candidate);
    const std::size_t distance = EditDistance(typed, candidate);
    const std::size_t near = std::max<std::size_t>(2, std::max(typed.size(), candidate.size()) / 3);
    if (distance <= near && (!best || distance < best_distance)) {
      best = candidate;
      best_distance = distance;
    }
  }
  if (best) return best;
  if (extensions.size() == 1) return extensions.front();
  return std::nullopt;
}

std::string DidYouMean(const std::string& typed, const std::vector<std::string>& candidates) {
  const std::optional<std::string> match = ClosestMatch(typed, candidates);
  return match ? "; did you mean '" + *match + "'?" : "";
}

}  // namespace cb::harness
