// SIGINT and SIGTERM ask a running path to stop rather than kill the process: the handlers
// only set a flag, which the path driver polls between iterations (SolveControls::interrupted),
// so that the run finishes the record line it is writing, keeps its records and exits with
// kExitInterrupted. The suite driver installs them first thing in main().
#pragma once

#include <signal.h>

#include <stdexcept>

namespace cb::harness {

// Where the harness itself does long work outside the path driver (writing the final state or
// a saved state, the cells of a large mesh), it checks for an interrupt as it goes and unwinds
// with this: the run ends with kExitInterrupted, the lines written so far whole.
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void InstallInterruptHandlers();

// For the length of a call from Python (python/module.cc): SIGINT (Ctrl-C, a notebook's
// interrupt) sets the flag as in the suite driver, so that the run stops the same way; the
// handler it replaced (Python's) is back afterwards, and the flag is cleared on both ends.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  struct sigaction previous_ {};
};

// True once SIGINT or SIGTERM arrived.
bool InterruptRequested();

// Throws Interrupted("interrupted while <doing>") once SIGINT or SIGTERM arrived.
void StopIfInterrupted(const char* doing);

// Takes note of the interrupt that stopped the path: InterruptRequested() is false again until
// the next signal, so that the records of what was done (the final state) are written, and a
// second signal stops those writes too.
void AcknowledgeInterrupt();

}  // namespace cb::harness
