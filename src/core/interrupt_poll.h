// Whether the program asked the work under way to stop (SIGINT, SIGTERM), for long work inside
// the library that cannot wait for the path driver's poll between iterations
// (SolveControls::interrupted): a direct factorisation of a large 3-D system can take minutes
// (core/abandonable_work.h). The program installs the poll; without one nothing is ever
// interrupted.
#pragma once

namespace cb {

// A poll safe to call from any thread at any time (e.g. a read of an atomic flag).
using InterruptPoll = bool (*)();

void SetInterruptPoll(InterruptPoll poll);

// The installed poll's answer; false without one.
bool InterruptPolled();

}  // namespace cb
