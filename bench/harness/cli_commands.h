// The commands of `contactbench` beside run and compare (commands.h) and plot
// (plot_command.h), one file each, and the dispatch that runs a parsed command (cli.cc).
#pragma once

#include "harness/options.h"
#include "harness/run_json.h"

namespace cb::harness {

// `contactbench list`: the problems with their parameters, the formulations and the solvers.
int ListCommand();
// `contactbench export`: the problem as a problem file (the suite's JSON, or FCLIB).
int ExportCommand(const RunArguments& a);
// `contactbench schema`: the record files' columns as markdown.
int SchemaCommand();
// `contactbench rerun DIR --out NEW`: the command DIR/run.json records, again.
int RerunCommand(const RunArguments& a);

// Runs a parsed command, its run record in `record`; the exit status.
int Execute(Command command, const RunArguments& a, RunJson* record);

}  // namespace cb::harness
