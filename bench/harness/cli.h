// The suite driver `contactbench`: list, run, compare, export, schema (options.h lists each
// command's options). Exit status: 0 every step verified, 2 bad arguments or a bad problem file
// (the message names the option, or the file and the JSON pointer of the bad value, and lists
// the valid choices), a problem too large for the memory, or an output directory that cannot be
// written (refused before any work), 3 the run stopped on a failure (a step, a stagnating path,
// a write, out of memory; records kept), 4 interrupted by SIGINT/SIGTERM (records kept).
#pragma once

namespace cb::harness {

constexpr int kExitOk = 0;
constexpr int kExitBadArguments = 2;
constexpr int kExitFailure = 3;
constexpr int kExitInterrupted = 4;

int Main(int argc, char** argv);

}  // namespace cb::harness
