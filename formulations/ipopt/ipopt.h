// Ipopt renderings of a step (issue 3): `ipopt-energy` (fixed-load energy minimisation subject
// to phi(u) <= 0) and `ipopt-mpcc` (the step as an NLP with complementarity reformulated).
#pragma once

#include <memory>

#include "formulations/config.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has Ipopt (CONTACTBENCH_HAVE_IPOPT).
bool IpoptAvailable();
std::unique_ptr<Formulation> MakeIpoptEnergy(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeIpoptMpcc(const FormulationConfig& config);

}  // namespace cb
