// The step as data, the verdict and run-time formulations for the module (step_bindings.cc).
#pragma once

#include <pybind11/pybind11.h>

namespace cb::harness {

void BindSteps(pybind11::module_& m);

}  // namespace cb::harness
