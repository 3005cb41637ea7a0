// `contactbench plot OUT_DIR`: runs the one plotting script of the suite, results/plot_run.py,
// on a run's records, so that the figures of the command and of the script are the same. The
// script is looked for where `cmake --install` puts it (PREFIX/share/contactbench, beside the
// installed binary's bin/) and then in the source tree the binary was built from.
#pragma once

#include <string>
#include <vector>

#include "harness/options.h"

namespace cb::harness {

// The places the script is looked for, in order.
std::vector<std::string> PlotScriptCandidates();

// Runs the script with Debian's /usr/bin/python3 (else python3 on the PATH) and returns the
// exit status: 0 figures written, 2 not a run's directory (the script's message), 3 the script
// failed. Throws InputError when no script is found.
int RunPlotScript(const RunArguments& arguments);

}  // namespace cb::harness
