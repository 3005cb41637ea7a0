// The processes a launcher started, read from its environment before MPI starts
// (src/parallel/processes.h): Open MPI's count first, then PMI's, and 1 for a value that is not a
// count, so that a stray variable never makes a run estimate or check for processes it lacks.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "parallel/processes.h"

namespace cb {
namespace {

// Sets (or, with nullopt, removes) an environment variable for the test's scope.
class ScopedVariable {
 public:
  ScopedVariable(const char* name, std::optional<std::string> value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      setenv(name, value->c_str(), 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedVariable() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedVariable(const ScopedVariable&) = delete;
  ScopedVariable& operator=(const ScopedVariable&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

int CountWith(std::optional<std::string> open_mpi, std::optional<std::string> pmi) {
  const ScopedVariable a("OMPI_COMM_WORLD_SIZE", std::move(open_mpi));
  const ScopedVariable b("PMI_SIZE", std::move(pmi));
  return LaunchedProcessCount();
}

TEST(LaunchedProcessesTest, TheLaunchersCountIsRead) {
  EXPECT_EQ(CountWith(std::nullopt, std::nullopt), 1);
  EXPECT_EQ(CountWith("4", std::nullopt), 4);
  EXPECT_EQ(CountWith(std::nullopt, "3"), 3);
  EXPECT_EQ(CountWith("2", "8"), 2);  // Open MPI's first
}

TEST(LaunchedProcessesTest, AValueThatIsNotACountIsOneProcess) {
  for (const char* bad : {"", "0", "-2", "2x", "1e3", "abc", "2000000"}) {
    EXPECT_EQ(CountWith(bad, std::nullopt), 1) << "'" << bad << "'";
  }
  EXPECT_EQ(CountWith("x", "5"), 5);  // a bad first falls through to the next
}

}  // namespace
}  // namespace cb
