#include "harness/process_agreement.h"

#include <climits>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/csv.h"
#include "harness/interrupt.h"
#include "harness/output_directory.h"
#include "parallel/processes.h"

namespace cb::harness {

namespace {

// The lowest process where `failed`, or INT_MAX where none (a collective).
int LowestFailing(bool failed) { return MinOverProcesses(failed ? ProcessRank() : INT_MAX); }

}  // namespace

bool InterruptedOnAnyProcess() { return AnyProcess(InterruptRequested()); }

namespace {

// The failure word of process 0 when it does not say how it ends: exit status 3.
constexpr int kFailedWord = 3;

// Process 0's word: 0 ready, else the exit status it ends with (a collective; the others'
// `word` is ignored).
int ProcessZeroSays(int word) { return BroadcastFromZero(word); }

// A file made and removed in `directory`: the directory process 0 prepared must be the one this
// process sees (a file system every process shares) and writable from here.
void ProbeDirectory(const std::string& directory) {
  const std::string probe =
      directory + "/.contactbench_write_test_" + std::to_string(ProcessRank());
  try {
    ProbeWritable(probe);
  } catch (const WriteError& e) {
    throw WriteError(probe, "process " + std::to_string(ProcessRank()) +
                                " cannot write there (is --out on a file system every "
                                "process shares?): " +
                                e.what());
  }
}

void ProbeOnEveryProcess(const std::string& directory) {
  OnEveryProcess("checking that it can write in " + directory, [&] { ProbeDirectory(directory); });
}

}  // namespace

void OnEveryProcess(const std::string& what, const std::function<void()>& work) {
  if (!Distributed()) {
    work();
    return;
  }
  std::exception_ptr failure;
  try {
    work();
  } catch (...) {
    failure = std::current_exception();
  }
  const int lowest = LowestFailing(failure != nullptr);
  if (failure) std::rethrow_exception(failure);
  if (lowest != INT_MAX) {
    throw std::runtime_error("process " + std::to_string(lowest) + " failed while " + what +
                             " (its standard error says why)");
  }
}

void AgreedRecords::OnAttempt(const StepAttempt& attempt) {
  OnEveryProcess("writing the records of a step", [&] {
    if (records_ != nullptr) records_->OnAttempt(attempt);
  });
}

void AgreedRecords::OnKink(const KinkRecord& kink) {
  OnEveryProcess("writing the record of a kink", [&] {
    if (records_ != nullptr) records_->OnKink(kink);
  });
}

void AgreedRecords::OnCriticalPoint(const CriticalPointRecord& point) {
  OnEveryProcess("writing the record of a critical point", [&] {
    if (records_ != nullptr) records_->OnCriticalPoint(point);
  });
}

OutputReadyWord::~OutputReadyWord() {
  if (!given_ && Distributed()) ProcessZeroSays(kFailedWord);
}

void OutputReadyWord::Ready(const std::string& directory) {
  if (given_ || !Distributed()) return;
  given_ = true;
  ProcessZeroSays(0);
  ProbeOnEveryProcess(directory);
}

void OutputReadyWord::Refused(int status) {
  if (given_ || !Distributed()) return;
  given_ = true;
  ProcessZeroSays(status == 0 ? kFailedWord : status);
}

int AwaitOutputReady(const std::string& directory) {
  if (!Distributed()) return 0;
  if (const int status = ProcessZeroSays(kFailedWord); status != 0) return status;
  ProbeOnEveryProcess(directory);
  return 0;
}

}  // namespace cb::harness
