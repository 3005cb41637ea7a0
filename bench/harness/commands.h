// `contactbench run` and `compare` as the suite driver (cli.cc) and the Python module
// (python/, docs/python.md) both call them: the same checks, the same path, the same records.
// The records go to the output directory of --out (prepared, locked, claimed, ended with
// run.json), or, given `memory` and no --out, to memory: each record file's text by its name
// ("steps.csv", "run.json"), the bytes the file would hold, and no file written (the saved
// states of --save-every need a directory and are refused there).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "harness/options.h"
#include "harness/record_schema.h"
#include "harness/run_json.h"
#include "problems/problem.h"
#include "step/formulation.h"

namespace cb::harness {

// The record files' texts by file name.
using RecordTexts = std::map<std::string, std::string>;

// Each returns the exit status of cli.h (the reason is in run.json) and throws UsageError or
// InputError for bad arguments (exit 2), Interrupted or WriteError while writing.
int RunCommand(const RunArguments& a, RunJson* record, RecordTexts* memory = nullptr);
int CompareCommand(const RunArguments& a, RunJson* record, RecordTexts* memory = nullptr);

// Whether run's formulation takes the problem's steps (Formulation::Accepts on the first
// step), with the reason when it does not: the catalogue's capability question.
bool AcceptsProblem(const RunArguments& a, std::string* reason);

// The problem of --problem NAME or --problem-file F, with --set applied. Bad input (an unknown
// name, a bad setting, an invalid problem file, too large for the memory) is an InputError.
Problem LoadProblem(const RunArguments& a);

// Runs `body` with its records in the output directory of --out (prepared, locked, claimed,
// ended with run.json whatever ends it) or, given `memory`, in memory; `body` returns the exit
// status and sets the reason.
int WithRecords(const RunArguments& a, RunJson* record, RecordTexts* memory,
                const std::function<int(const RecordTarget&, std::string* reason)>& body);

// Formulation `name` with the common settings and its own --option values (refused as bad
// arguments, with the closest known key for an unknown one).
std::unique_ptr<Formulation> MakeConfiguredFormulation(const RunArguments& a,
                                                       const std::string& name);

// Refuses an output directory that cannot be written before any work starts: created if
// missing, then probed with a file (permissions alone do not tell: root, read-only mounts).
void PrepareOutput(const std::string& dir);

}  // namespace cb::harness
