#pragma once

#include <cstdio>
#include <string>

namespace cb {

// Holds what a library writes to the process's standard error while it is in scope (Siconos's
// dense solvers report a singular LAPACK factorisation there, with no switch to turn it off), so
// that nothing below the harness prints: Release() hands the text back for the step's details.
// Where the descriptors cannot be redirected, nothing is captured and the output goes through.
class CapturedStderr {
 public:
  CapturedStderr();
  ~CapturedStderr();
  CapturedStderr(const CapturedStderr&) = delete;
  CapturedStderr& operator=(const CapturedStderr&) = delete;

  // Restores standard error and returns what was written to it meanwhile.
  std::string Release();

 private:
  std::FILE* sink_ = nullptr;
  int saved_ = -1;
};

// At most `max_chars` of `text`, cut at a line end when one is near, with the count of lines
// left out: library output kept in a record's details stays one short field.
std::string AbbreviateOutput(const std::string& text, std::size_t max_chars = 400);

}  // namespace cb
