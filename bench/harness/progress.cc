#include "harness/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace cb::harness {

std::string ClockText(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  const long hours = total / 3600;
  const long minutes = total / 60 % 60;
  const long secs = total % 60;
  char text[32];
  if (hours > 0) {
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", hours, minutes, secs);
  } else {
    std::snprintf(text, sizeof text, "%ld:%02ld", minutes, secs);
  }
  return text;
}

std::string TimeText(double elapsed_s, int done, int total) {
  std::string text = "elapsed " + ClockText(elapsed_s);
  if (done > 0 && done < total) {
    text += ", left ~" + ClockText(elapsed_s / done * (total - done));
  }
  return text;
}

ProgressLine::ProgressLine(std::FILE* stream)
    : stream_(stream), enabled_(isatty(fileno(stream)) == 1) {}

void ProgressLine::Update(const std::string& text, int done, int total) {
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // "\x1b[K" (erase to the end of the line) clears what a longer earlier text left.
  std::fprintf(stream_, "\r%s  %s\x1b[K", text.c_str(), TimeText(elapsed, done, total).c_str());
  std::fflush(stream_);
  open_ = true;
}

void ProgressLine::End() {
  if (!open_) return;
  std::fputc('\n', stream_);
  std::fflush(stream_);
  open_ = false;
}

}  // namespace cb::harness
