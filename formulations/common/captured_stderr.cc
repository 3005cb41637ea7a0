#include "formulations/common/captured_stderr.h"

#include <unistd.h>

#include <algorithm>

namespace cb {

CapturedStderr::CapturedStderr() {
  std::fflush(stderr);
  sink_ = std::tmpfile();
  if (sink_ == nullptr) return;
  saved_ = dup(STDERR_FILENO);
  if (saved_ < 0 || dup2(fileno(sink_), STDERR_FILENO) < 0) {
    if (saved_ >= 0) close(saved_);
    saved_ = -1;
    std::fclose(sink_);
    sink_ = nullptr;
  }
}

CapturedStderr::~CapturedStderr() { Release(); }

std::string CapturedStderr::Release() {
  if (sink_ == nullptr) return {};
  std::fflush(stderr);
  dup2(saved_, STDERR_FILENO);
  close(saved_);
  saved_ = -1;
  std::string text;
  std::rewind(sink_);
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, sink_)) > 0) text.append(buffer, got);
  std::fclose(sink_);
  sink_ = nullptr;
  return text;
}

std::string AbbreviateOutput(const std::string& text, std::size_t max_chars) {
  std::string kept = text;
  while (!kept.empty() && (kept.back() == '\n' || kept.back() == ' ')) kept.pop_back();
  if (kept.size() <= max_chars) return kept;
  std::size_t cut = kept.rfind('\n', max_chars);
  if (cut == std::string::npos || cut < max_chars / 2) cut = max_chars;
  std::size_t rest = cut;
  if (kept[rest] == '\n') ++rest;
  const auto left_out =
      1 + std::count(kept.begin() + static_cast<std::ptrdiff_t>(rest), kept.end(), '\n');
  return kept.substr(0, cut) + " ... (" + std::to_string(left_out) + " more lines)";
}

}  // namespace cb
