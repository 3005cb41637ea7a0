// `contactbench compare --problem-dir`: a problem set, the way the FCLIB literature compares
// solvers (Acary, Bremond & Huber, INRIA RR-9118): every formulation on every problem of a
// collection, each a single fixed-load solve, cold and from each of the file's guesses; one row
// per problem x formulation x start in problems.csv (and one per file that cannot be read),
// with the verdict's status, the iterations, the time (median, min and max of --repeat N
// solves) and the FCLIB error of the answer (docs/comparison.md, "Problem sets"). The solves'
// attempts and iterations also go to steps.csv and iterations.csv, labelled with their problem.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/commands.h"
#include "step/step_problem.h"

namespace cb::harness {

// The problem files --problem-dir names: each comma-separated item a directory (its FCLIB
// files, .hdf5 and .h5, and its JSON problem files, .json, sorted by name) or a file. Throws
// InputError for an item that is neither, a directory without such files, or a file named
// twice. (A file that is named but cannot be read is a row of problems.csv, not a refusal.)
std::vector<std::string> ProblemSetFiles(const std::string& items);

// compare --problem-dir (CompareCommand passes it on): the exit status of cli.h.
int ProblemSetCommand(const RunArguments& a, RunJson* record, RecordTexts* memory);

// run --start guess:K: the file's /guesses/K as a state of `problem` (read from
// a.problem_file), or nothing without --start guess:K. Throws InputError for a problem that is
// not an FCLIB file or a K beyond its guesses.
std::optional<State> GuessStart(const RunArguments& a, const Problem& problem);

}  // namespace cb::harness
