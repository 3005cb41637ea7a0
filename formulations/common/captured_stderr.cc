#include "formulations/common/captured_stderr.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <system_error>
#include <utility>

namespace cb {

namespace {

// Appends what `from` delivers to *text: until every write end is closed or, once `stop` is
// readable, until the pipe is empty (a copy of the write end elsewhere, say in a child process,
// must not keep the reader, and so Release, waiting).
void Drain(int from, int stop, std::string* text) {
  char buffer[4096];
  auto read_some = [&]() {
    ssize_t got = 0;
    do got = read(from, buffer, sizeof buffer);
    while (got < 0 && errno == EINTR);
    if (got > 0) text->append(buffer, static_cast<std::size_t>(got));
    return got > 0;
  };
  pollfd watched[2] = {{from, POLLIN, 0}, {stop, POLLIN, 0}};
  for (;;) {
    if (poll(watched, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (watched[0].revents != 0) {
      if (read_some()) continue;
      return;  // end of file: no writer is left
    }
    if (watched[1].revents != 0) break;
  }
  fcntl(from, F_SETFL, fcntl(from, F_GETFL) | O_NONBLOCK);
  while (read_some()) {
  }
}

void CloseBoth(const int (&ends)[2]) {
  close(ends[0]);
  close(ends[1]);
}

}  // namespace

CapturedStderr::CapturedStderr() {
  std::fflush(stderr);
  int output[2], stop[2];
  if (pipe2(output, O_CLOEXEC) != 0) return;
  if (pipe2(stop, O_CLOEXEC) != 0) {
    CloseBoth(output);
    return;
  }
  saved_ = fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
  try {
    if (saved_ < 0) throw std::system_error(errno, std::generic_category());
    reader_ = std::thread([from = output[0], until = stop[0], text = &text_] {
      Drain(from, until, text);
      close(from);
    });
  } catch (const std::system_error&) {
    if (saved_ >= 0) close(saved_);
    saved_ = -1;
    CloseBoth(output);
    CloseBoth(stop);
    return;
  }
  stop_[0] = stop[0];
  stop_[1] = stop[1];
  if (dup2(output[1], STDERR_FILENO) < 0) {
    close(output[1]);
    Release();  // ends the reader; nothing was captured
    return;
  }
  close(output[1]);  // descriptor 2 is now the pipe's only write end
}

CapturedStderr::~CapturedStderr() { Release(); }

std::string CapturedStderr::Release() {
  if (!reader_.joinable()) return {};
  std::fflush(stderr);
  dup2(saved_, STDERR_FILENO);
  close(saved_);
  saved_ = -1;
  // The reader may have ended already (end of file once descriptor 2 is restored): the stop
  // pipe's read end stays open until it is joined, so this write cannot raise SIGPIPE.
  const char done = 0;
  while (write(stop_[1], &done, 1) < 0 && errno == EINTR) {
  }
  reader_.join();
  CloseBoth(stop_);
  stop_[0] = stop_[1] = -1;
  std::string text = std::move(text_);
  text_.clear();
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
