#include "formulations/common/captured_stderr.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <string>

namespace cb {
namespace {

TEST(CapturedStderr, HoldsWhatBothStdioAndTheDescriptorWrite) {
  CapturedStderr capture;
  std::fprintf(stderr, "NM_LU_factorize: DGETRF failed\n");
  const char raw[] = "written to descriptor 2\n";
  ASSERT_EQ(write(STDERR_FILENO, raw, sizeof raw - 1), static_cast<ssize_t>(sizeof raw - 1));
  EXPECT_EQ(capture.Release(), "NM_LU_factorize: DGETRF failed\nwritten to descriptor 2\n");
}

TEST(CapturedStderr, RestoresStandardErrorOnRelease) {
  {
    CapturedStderr first;
    std::fprintf(stderr, "first\n");
    EXPECT_EQ(first.Release(), "first\n");
    EXPECT_EQ(first.Release(), "");  // a second release has nothing left
  }
  // Standard error is the original again: a new capture sees only what is written after it.
  CapturedStderr second;
  std::fprintf(stderr, "second\n");
  EXPECT_EQ(second.Release(), "second\n");
}

TEST(CapturedStderr, PrintsNothingOfWhatItHolds) {
  // An outer capture stands for the terminal: what the inner one holds never reaches it.
  CapturedStderr terminal;
  {
    CapturedStderr inner;
    std::fprintf(stderr, "held\n");
    EXPECT_EQ(inner.Release(), "held\n");
  }
  std::fprintf(stderr, "after\n");
  EXPECT_EQ(terminal.Release(), "after\n");
}

TEST(CapturedStderr, HoldsMoreThanThePipeWithoutBlocking) {
  // Many times a pipe's capacity (64 KiB on Linux), written while the capture is in scope: the
  // writer would block for good if nothing drained the pipe until Release.
  const std::size_t size = 4 << 20;
  const std::string chunk(1000, 'x');
  CapturedStderr capture;
  std::size_t written = 0;
  while (written < size) {
    const ssize_t got = write(STDERR_FILENO, chunk.data(), chunk.size());
    ASSERT_GT(got, 0);
    written += static_cast<std::size_t>(got);
  }
  std::fprintf(stderr, "end\n");
  const std::string text = capture.Release();
  EXPECT_EQ(text.size(), written + 4);
  EXPECT_EQ(text.substr(text.size() - 4), "end\n");
  EXPECT_EQ(text.find_first_not_of('x'), written);
}

TEST(CapturedStderr, ReleasesWhenTheReaderHasAlreadyEnded) {
  // Restoring descriptor 2 closes the pipe's last write end, so the reader may see end of file
  // and end before Release tells it to stop: telling it must not raise SIGPIPE then.
  for (int i = 0; i < 2000; ++i) {
    CapturedStderr capture;
    std::fprintf(stderr, "%d\n", i);
    ASSERT_EQ(capture.Release(), std::to_string(i) + "\n");
  }
}

TEST(AbbreviateOutput, KeepsShortTextAndCutsLongTextAtALineEnd) {
  EXPECT_EQ(AbbreviateOutput("one line\n"), "one line");
  std::string lines;
  for (int i = 0; i < 100; ++i) lines += "line " + std::to_string(i) + "\n";
  const std::string cut = AbbreviateOutput(lines, 40);
  EXPECT_LE(cut.find(" ... ("), 40u);
  EXPECT_EQ(cut.substr(0, 14), "line 0\nline 1\n");
  // 40 characters hold "line 0".."line 4" and their newlines (35 characters): the other 95 of
  // the 100 lines are left out.
  EXPECT_EQ(cut, lines.substr(0, 34) + " ... (95 more lines)");
}

}  // namespace
}  // namespace cb
