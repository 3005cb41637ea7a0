// Long work inside the library that an interrupt must be able to cut short although the code
// doing it has no hook to stop it: a direct factorisation of a large 3-D system (KLU's, CHOLMOD's)
// can take minutes, and a SIGTERM waited for it (73 s and 36 s; issue 30). The work runs on a
// worker thread; the calling thread waits, polling InterruptPolled() (core/interrupt_poll.h)
// every 0.1 s, and on an interrupt abandons the worker and returns at once.
//
// Why this is sound: the work and its release touch only what they own (captured by value or
// through a shared_ptr, never the caller's objects), so the caller may free its own and return;
// the abandoned worker frees what it owns when the work ends (`release`), or dies with the
// process, which may exit under it since the work only computes and allocates, provided the
// exit runs no static destructors (AbandonedWorkRunning, below). The alternatives
// are not: a flag checked inside the library needs a patched library, and cancelling a thread
// inside it would leave its allocations and possibly the allocator's lock half done.
#pragma once

#include <functional>

namespace cb {

// A factorisation (or analysis) of a matrix with fewer stored entries runs on the calling
// thread: a thread costs ~0.1 ms, and such a factorisation takes well under a second. One
// threshold for every solver that hands its work to a worker.
constexpr long kAbandonableMinNonZeros = 200000;

enum class WorkEnd {
  kFinished,                // `work` ran to its end (on the calling thread if no thread was had)
  kInterruptedBeforeStart,  // an interrupt was pending: neither `work` nor `release` runs
  kAbandoned,               // interrupted during `work`: the worker runs `release` after it
};

// Runs `work` on a worker thread named `thread_name` (at most 15 characters, so that it can be
// told apart in /proc/PID/task/*/comm) while the calling thread waits as above.
WorkEnd RunAbandonably(const char* thread_name, std::function<void()> work,
                       std::function<void()> release);

// Whether an abandoned worker is still at its work. The program must then end without running
// static destructors (std::_Exit after flushing): the work may be inside a library whose
// process-wide state they tear down (OpenBLAS's buffers under CHOLMOD's supernodal factor or
// dpotrf: a SIGTERM during P1's or hertz-3d's first iteration crashed at exit, issue 30).
bool AbandonedWorkRunning();

// For tests: called on each worker thread, with its name, before its work starts (nullptr: none).
// A hook that waits there until the interrupt is polled makes an abandonment certain however
// short the work is, so a test needs no problem that is slow to factorise.
using WorkerStartHook = void (*)(const char* thread_name);
void SetWorkerStartHookForTesting(WorkerStartHook hook);

}  // namespace cb
