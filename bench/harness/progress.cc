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

std::string LineText(const std::string& text, double elapsed_s, int done, int total,
                     const std::string& notice) {
  std::string line = "\r" + text + "  " + TimeText(elapsed_s, done, total);
  if (!notice.empty()) line += "  [" + notice + "]";
  return line + "\x1b[K";  // erase to the end of the line: what a longer earlier text left
}

std::string SlowWorkText(const SlowWork& work) {
  return work.from + " fell back to " + work.to + " on a " + std::to_string(work.rows) + " x " +
         std::to_string(work.rows) + " 3-D system: minutes per factorisation";
}

namespace {

// The line that shows the library's reports of slow work, if any (only the thread that runs
// the path reports, and it is the one that owns the line).
ProgressLine* g_showing_slow_work = nullptr;

void OnSlowWork(const SlowWork& work) {
  if (g_showing_slow_work != nullptr) g_showing_slow_work->Notice(SlowWorkText(work));
}

}  // namespace

ProgressLine::ProgressLine(std::FILE* stream)
    : stream_(stream), enabled_(isatty(fileno(stream)) == 1) {}

ProgressLine::~ProgressLine() {
  if (g_showing_slow_work == this) {
    SetSlowWorkListener(nullptr);
    g_showing_slow_work = nullptr;
  }
  End();
}

void ProgressLine::Update(const std::string& text, int done, int total) {
  text_ = text;
  done_ = done;
  total_ = total;
  Notice("");
}

void ProgressLine::ShowSlowWork() {
  g_showing_slow_work = this;
  SetSlowWorkListener(OnSlowWork);
}

void ProgressLine::Notice(const std::string& notice) {
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fputs(LineText(text_, elapsed, done_, total_, notice).c_str(), stream_);
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
