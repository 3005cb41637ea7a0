// The names of the coordinate directions in problem files ("fixed": ["x", "y"],
// "direction": "z"), which the reader and the writer share.
#pragma once

namespace cb::io {

inline constexpr const char* kDirectionNames[3] = {"x", "y", "z"};

}  // namespace cb::io
