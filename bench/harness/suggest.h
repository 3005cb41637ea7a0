// "Did you mean ...?": the valid name closest to a mistyped one (an option, a command, a
// formulation, a problem, a solver), by edit distance, so that an error names the fix.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cb::harness {

// The Levenshtein distance: insertions, deletions and substitutions of one character.
std::size_t EditDistance(const std::string& a, const std::string& b);

// The candidate nearest to `typed` when it is near enough to be a typo: at most a third of the
// longer name's characters (at least 2) apart, or `typed` a prefix of exactly one candidate.
// Ties go to the first candidate. nullopt when none is near.
std::optional<std::string> ClosestMatch(const std::string& typed,
                                        const std::vector<std::string>& candidates);

// "; did you mean 'X'?" for the closest match, or "".
std::string DidYouMean(const std::string& typed, const std::vector<std::string>& candidates);

}  // namespace cb::harness
