#pragma once

#include <cstddef>
#include <string>
#include <thread>

namespace cb {

// Holds what a library writes to the process's standard error while it is in scope (Siconos's
// dense solvers report a singular LAPACK factorisation there, with no switch to turn it off), so
// that nothing below the harness prints: Release() hands the text back for the step's details.
// Descriptor 2 is the write end of a pipe meanwhile, kept in memory by a reader thread that
// drains it as it fills, so a library that writes more than the pipe holds never blocks; no file
// is written. Where the pipe or the thread cannot be had, nothing is captured and the output
// goes through.
class CapturedStderr {
 public:
  CapturedStderr();
  ~CapturedStderr();
  CapturedStderr(const CapturedStderr&) = delete;
  CapturedStderr& operator=(const CapturedStderr&) = delete;

  // Restores standard error and returns what was written to it meanwhile.
  std::string Release();

 private:
  int saved_ = -1;          // the original standard error, while captured
  int stop_[2] = {-1, -1};  // a pipe that tells the reader standard error is restored
  std::thread reader_;
  std::string text_;  // the reader's until it is joined
};

// At most `max_chars` of `text`, cut at a line end when one is near, with the count of lines
// left out: library output kept in a record's details stays one short field.
std::string AbbreviateOutput(const std::string& text, std::size_t max_chars = 400);

}  // namespace cb
