#include "harness/plugins.h"

#include <dlfcn.h>

#include <stdexcept>

#include "formulations/external/plugin.h"
#include "harness/options.h"

namespace cb::harness {

std::vector<std::string> PluginPaths(const std::vector<std::string>& args) {
  std::vector<std::string> paths;
  const std::string option = "--plugin";
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == option && i + 1 < args.size()) {
      paths.push_back(args[++i]);
    } else if (args[i].rfind(option + "=", 0) == 0) {
      paths.push_back(args[i].substr(option.size() + 1));
    }
  }
  return paths;
}

void LoadPlugin(const std::string& path) {
  // A path without '/' would be searched for on the library path: name the file given.
  const std::string file = path.find('/') == std::string::npos ? "./" + path : path;
  // Never closed: its formulations' code must outlive the registry entries.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) throw UsageError("--plugin " + path + ": cannot load: " + dlerror());
  void* symbol = dlsym(handle, kPluginEntryPoint);
  if (symbol == nullptr) {
    throw UsageError("--plugin " + path + ": no entry point " + kPluginEntryPoint +
                     " (formulations/external/plugin.h)");
  }
  PluginHost host;
  host.register_formulation = [](FormulationInfo info) { RegisterFormulation(std::move(info)); };
  try {
    reinterpret_cast<PluginEntryPoint>(symbol)(host);  // NOLINT: dlsym's documented use
  } catch (const std::invalid_argument& e) {
    throw UsageError("--plugin " + path + ": " + e.what());
  }
}

}  // namespace cb::harness
