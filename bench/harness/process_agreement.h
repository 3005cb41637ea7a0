// What the processes of a distributed run (formulations/petsc_dist/petsc_dist.h) agree on when
// more than process 0 writes: that process 0 has made the output directory ready, and whether
// a write failed anywhere. A failure on one process is then a failure on all of them, at the
// same point, and no process is left waiting for another that has given up. With one process
// these calls only run the work (no MPI).
#pragma once

#include <functional>
#include <string>

#include "path/path.h"

namespace cb::harness {

// Runs `work` on this process; then, a collective (every process calls it at the same point),
// throws on every process when it threw on any: there its own exception, elsewhere a
// std::runtime_error naming the lowest failing process and `what` it was doing.
void OnEveryProcess(const std::string& what, const std::function<void()>& work);

// Whether SIGINT or SIGTERM reached any process (a collective in a distributed run; with one
// process, InterruptRequested()). The path driver's decision to stop before a solve or after a
// step is then the same on every process: a signal to one process alone made it skip a solve
// the others entered, and their collectives then paired with the wrong ones (a failure, and
// run.json's counts at 0 beside the rows of steps.csv; issue 30). Every process must ask at
// the same points, as the path driver does (SolveControls::interrupted).
bool InterruptedOnAnyProcess();

// Process 0's records of the path, agreed with the other processes at every event: each
// process of a distributed run wraps its own writer (process 0 its records, the others
// nothing, `records` null) so that every event is one OnEveryProcess, at the same point of the
// path on every process. A record write that fails on process 0 (a full disk) then stops every
// process there together, each unwinding the same solver objects, whose destructors are
// collectives too; without the agreement process 0 would unwind alone and wait in a destructor
// for processes that wait in the next solve (issue 30). Put it before the other observers of a
// tee, so that each process enters its later collectives (the saved states) in the same order.
class AgreedRecords final : public PathObserver {
 public:
  explicit AgreedRecords(PathObserver* records) : records_(records) {}
  void OnAttempt(const StepAttempt& attempt) override;
  void OnKink(const KinkRecord& kink) override;
  void OnCriticalPoint(const CriticalPointRecord& point) override;

 private:
  PathObserver* records_;
};

// Process 0's word to the others that the output directory is ready (created, claimed, its
// vtk/ folder made): Ready() gives it once; if it never did, the destructor gives the word of a
// failure instead, so that the others stop rather than wait for a process 0 that failed before.
// With one process, nothing.
class OutputReadyWord {
 public:
  OutputReadyWord() = default;
  ~OutputReadyWord();
  OutputReadyWord(const OutputReadyWord&) = delete;
  OutputReadyWord& operator=(const OutputReadyWord&) = delete;

  // Then every process checks that it can write in `directory` (OnEveryProcess).
  void Ready(const std::string& directory);
  // The word that process 0 refused the run with exit `status` (a bad --out: 2), so that
  // every process ends with the status process 0 ends with; the destructor's word is 3.
  void Refused(int status);

 private:
  bool given_ = false;
};

// The other processes' side: waits for process 0's word; 0 when the directory is ready (then
// checks, with every process, that this one can write in `directory`), else the exit status
// process 0 ends with (it says why).
int AwaitOutputReady(const std::string& directory);

}  // namespace cb::harness
