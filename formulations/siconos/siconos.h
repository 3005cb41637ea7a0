// The Siconos numerics backend: `siconos-lemke`, `siconos-newton-fb` and `siconos-newton-min`,
// Siconos's LCP solvers on the dense LCP of a fixed-load step (siconos_lcp.h: an LCP as it is,
// or a linear model after eliminating the displacements), through the adapter of
// siconos_adapter.h. Without Siconos, siconos_stub.cc stands in (siconos.cmake chooses).
#pragma once

#include <memory>
#include <string>

#include "formulations/common/config.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has Siconos numerics (defined by the adapter, or false by the stub).
bool SiconosAvailable();
// The version of Siconos numerics this build is linked with, from its headers or library; ""
// without it.
std::string SiconosVersion();
// Registry factories; without Siconos they throw std::invalid_argument.
std::unique_ptr<Formulation> MakeSiconosLemke(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeSiconosNewtonFb(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeSiconosNewtonMin(const FormulationConfig& config);

}  // namespace cb
