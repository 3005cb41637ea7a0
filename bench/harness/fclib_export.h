// `contactbench export --format fclib` with the suite's answer (docs/problem-files.md,
// "Writing"): a fixed-load problem is solved once by implicit-fb from the unloaded state (as
// `run` solves it) and its verified answer written as /solution; with --step N, step N of the
// problem's path (traced by implicit-fb as `run` traces it) is written as a fixed-load problem
// at that step's load, its answer as /solution and the state of step N - 1 (the unloaded state
// for N = 1) as /guesses/1, the start a path solver would take.
#pragma once

#include <string>

#include "harness/options.h"
#include "problems/problem.h"

namespace cb::harness {

// Writes a.out; returns what was written, for the summary line. Throws InputError for a problem
// FCLIB cannot hold (nonlinear, no energy) or a --step that does not fit the problem, before
// any solve, and std::runtime_error when the path stops before step N.
std::string ExportFclib(const RunArguments& a, const Problem& problem);

}  // namespace cb::harness
