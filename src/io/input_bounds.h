// The bounds on an input's size and shape that are checked before it is parsed, so that a
// file far larger or deeper than any problem is refused at once rather than after minutes and
// gigabytes (issue 30: a 200 MB problem file took 5 GB before it failed; docs/hardening.md,
// "Bounded inputs").
#pragma once

#include <cstdint>
#include <string>

namespace cb::io {

// A problem file's largest size by default. The largest problem files of the suite are well
// under a megabyte (meshes of 3-D problems are Gmsh files of their own); an LCP's matrix of a
// few thousand rows fits. `--allow-memory` lifts the bound.
inline constexpr std::uintmax_t kProblemFileMaxBytes = std::uintmax_t{64} << 20;

// The deepest nesting of arrays and objects a problem file may have: its schema nests 4 deep
// (an LCP's {"M": {"entries": [[i, j, value]]}}); a parser's work and its recursion grow with
// the depth of a hostile file, so it is refused before parsing.
inline constexpr int kJsonMaxDepth = 32;

// Throws InputError naming `file` and the line and column where the
// nesting of `text` first exceeds `max_depth`. A scan of the text: strings and escapes are
// skipped, nothing is allocated.
void CheckJsonDepth(const std::string& text, const std::string& file, int max_depth);

}  // namespace cb::io
