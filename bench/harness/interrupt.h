// SIGINT and SIGTERM ask a running path to stop rather than kill the process: the handlers
// only set a flag, which the path driver polls between iterations (SolveControls::interrupted),
// so that the run finishes the record line it is writing, keeps its records and exits with
// kExitInterrupted. The suite driver installs them first thing in main().
#pragma once

namespace cb::harness {

void InstallInterruptHandlers();

// True once SIGINT or SIGTERM arrived.
bool InterruptRequested();

}  // namespace cb::harness
