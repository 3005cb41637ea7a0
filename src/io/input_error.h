// The one error type of the input readers: a bad problem file, mesh file or complementarity
// input. It derives from std::invalid_argument so that every caller that already treats
// std::invalid_argument as "bad input" (the CLI's exit status 2) handles it unchanged.
#pragma once

#include <stdexcept>
#include <string>

namespace cb::io {

class InputError : public std::invalid_argument {
 public:
  // "FILE: WHERE: REASON", WHERE a JSON pointer ("/members/3/E") or "line N" (mesh files);
  // an empty WHERE is left out.
  InputError(const std::string& file, const std::string& where, const std::string& reason)
      : std::invalid_argument(file + ": " + (where.empty() ? "" : where + ": ") + reason) {}
};

}  // namespace cb::io
