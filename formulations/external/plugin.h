// The registration entry point of a C++ plug-in (docs/your-own-method.md): a shared object,
// compiled on its own against the installed package, that `contactbench run|compare|list
// --plugin FILE` loads before reading the other options. It exports
//
//   extern "C" void contactbench_register_formulations(const cb::PluginHost& host);
//
// which calls host.register_formulation once per formulation (ExternalFormulationInfo of
// callback_formulation.h for a method on the step system, or a FormulationInfo whose factory
// makes any cb::Formulation). Registration goes through the host's function, so it reaches the
// driver's registry whatever copy of the libraries the plug-in carries; a name already taken is
// refused (std::invalid_argument), and the driver refuses the plug-in with exit status 2.
#pragma once

#include "formulations/registry.h"

namespace cb {

struct PluginHost {
  void (*register_formulation)(FormulationInfo info) = nullptr;
};

// The symbol the driver looks up, and its type.
inline constexpr const char* kPluginEntryPoint = "contactbench_register_formulations";
using PluginEntryPoint = void (*)(const PluginHost& host);

}  // namespace cb
