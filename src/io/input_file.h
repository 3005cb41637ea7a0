// Reads an input file (a problem file, a mesh file) whole. Only a regular file is read: a
// directory, a FIFO or a device (/dev/zero) would block or never end, or fail later with a
// message about its content that hides what was given.
#pragma once

#include <cstdint>
#include <string>

namespace cb::io {

// The text of the file at `path`; `what` names it in errors ("problem file", "mesh file").
// Throws InputError when it is missing, not a regular file, or cannot be read, and, before
// reading anything, when it is larger than `max_bytes` (0: no bound; `lifted_by` names the
// option that lifts the bound, for the message).
std::string ReadInputFile(const std::string& path, const std::string& what,
                          std::uintmax_t max_bytes = 0, const std::string& lifted_by = "");

}  // namespace cb::io
