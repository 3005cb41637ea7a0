// The suite driver `contactbench`: list, run. Exit status: 0 every step verified, 2 bad
// arguments (with a message listing the valid choices), 3 the run stopped on a failure (records
// kept), 4 interrupted by SIGINT/SIGTERM (records kept).
#pragma once

namespace cb::harness {

constexpr int kExitOk = 0;
constexpr int kExitBadArguments = 2;
constexpr int kExitFailure = 3;
constexpr int kExitInterrupted = 4;

int Main(int argc, char** argv);

}  // namespace cb::harness
