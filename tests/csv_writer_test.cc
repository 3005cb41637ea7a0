// The CSV writer on a failing file: nothing is silently lost, no half line stays.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/csv.h"

namespace {

std::string Contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A lower file size limit for the test's lifetime (unprivileged: only the soft limit drops), so
// that a write past it fails part-way as on a full disk; SIGXFSZ is ignored meanwhile so that
// the write returns EFBIG rather than killing the process.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lowered = saved_;
    lowered.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lowered);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = nullptr;
};

TEST(CsvWriterTest, AHeaderThatCannotBeWrittenThrowsNamingTheFile) {
  // /dev/full refuses every write with ENOSPC, as a full disk does.
  try {
    cb::CsvWriter csv("/dev/full", {"a", "b"});
    FAIL() << "the header write to /dev/full did not throw";
  } catch (const cb::WriteError& e) {
    EXPECT_EQ(e.path(), "/dev/full");
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
  }
}

TEST(CsvWriterTest, AShortWriteIsCutBackToTheLastWholeLineAndThrows) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "contactbench_csv_short_write.csv").string();
  std::filesystem::remove(path);
  const rlim_t limit = 100;  // the header and a few rows fit, then a row is cut
  std::string written;
  bool threw = false;
  {
    const FileSizeLimit guard(limit);
    cb::CsvWriter csv(path, {"step", "value"});
    written = "step,value\n";
    for (int step = 0; step < 100 && !threw; ++step) {
      cb::CsvWriter::Row row;
      row << step << 1.42e-13;
      try {
        csv.Write(row);
        written += std::to_string(step) + ",1.42e-13\n";
      } catch (const cb::WriteError& e) {
        threw = true;
        EXPECT_EQ(e.path(), path);
      }
    }
  }
  ASSERT_TRUE(threw) << "no write failed under a " << limit << "-byte limit";
  // Exactly the rows whose Write returned, each whole: no "1.4" left of a cut "1.42e-13".
  EXPECT_EQ(Contents(path), written);
  EXPECT_LE(written.size(), limit);
  std::filesystem::remove(path);
}

}  // namespace
