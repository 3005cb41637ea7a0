// `--plugin FILE` (formulations/external/plugin.h): plug-ins are loaded before the options are
// parsed, so that their formulations are names the parser knows (--formulation, --formulations,
// --option NAME:KEY=VALUE, the suggestions).
#pragma once

#include <string>
#include <vector>

namespace cb::harness {

// The values of every `--plugin FILE` / `--plugin=FILE` among a command's arguments.
std::vector<std::string> PluginPaths(const std::vector<std::string>& args);

// Loads the shared object and calls its entry point. Throws UsageError naming the file and the
// reason: it cannot be loaded (dlerror's message), it has no entry point, or it registers a
// name already registered (or a bad one).
void LoadPlugin(const std::string& path);

}  // namespace cb::harness
