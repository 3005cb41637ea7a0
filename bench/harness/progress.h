// The progress line of a run on a terminal: one line rewritten in place with what the run is
// doing, the elapsed time and an estimate of the time left. Nothing is shown when the stream is
// not a terminal (a log file, a pipe), so records of a batch run hold no carriage returns.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "core/slow_work.h"

namespace cb::harness {

// "1:05" (minutes:seconds) or "2:03:09" (hours:minutes:seconds) of a non-negative duration.
std::string ClockText(double seconds);

// The text after a run's own: "elapsed E", and when 0 < done < total "left ~L", L estimated
// as the elapsed time per step done times the steps left.
std::string TimeText(double elapsed_s, int done, int total);

// The line as shown: `text`, the times after `done` of `total` steps, and `notice` when not
// empty; "\r" first and erase-to-end-of-line last, so a shorter line leaves nothing behind.
std::string LineText(const std::string& text, double elapsed_s, int done, int total,
                     const std::string& notice);

// The notice for a fall-back the library reports (core/slow_work.h) in a 3-D problem, whose
// direct factorisation fills O(d sqrt(s)) entries (docs/hardening.md, Memory): KLU took ~90 s
// a factorisation on hertz-3d, minutes an iteration.
std::string SlowWorkText(const SlowWork& work);

class ProgressLine {
 public:
  // Shown on `stream` only when it is a terminal.
  explicit ProgressLine(std::FILE* stream = stderr);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // Rewrites the line with `text` and the times after `done` of `total` steps; the rest of the
  // terminal line is cleared, so a shorter text leaves nothing of a longer one behind.
  void Update(const std::string& text, int done, int total);
  // Ends a shown line with a newline, so that the next message starts a line of its own.
  void End();
  // From now on until this line ends its life, shows the library's reports of slow work
  // (core/slow_work.h) after the last text, until the next Update.
  void ShowSlowWork();
  // Rewrites the line with the last text and `notice` after it.
  void Notice(const std::string& notice);

 private:
  std::FILE* stream_;
  std::string text_;  // of the last Update
  int done_ = 0, total_ = 0;
  bool enabled_ = false;
  bool open_ = false;  // a line is shown and not yet ended
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace cb::harness
