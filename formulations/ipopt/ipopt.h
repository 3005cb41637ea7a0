// The Ipopt backend: `ipopt-energy` (fixed-load energy minimisation subject to phi(u) <= 0,
// ipopt_energy.cc) and `ipopt-mpcc` (the step as an NLP with complementarity reformulated,
// ipopt_mpcc.cc), on the NLPs of ipopt_nlp.h through the adapter of ipopt_adapter.h. Without
// Ipopt, ipopt_stub.cc stands in (ipopt.cmake chooses).
#pragma once

#include <memory>
#include <string>

#include "formulations/common/config.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has Ipopt (defined by the adapter, or false by the stub).
bool IpoptAvailable();
// The version of Ipopt this build is linked with, from its headers or library; "" without it.
std::string IpoptVersion();
// Registry factories; without Ipopt they throw std::invalid_argument.
std::unique_ptr<Formulation> MakeIpoptEnergy(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeIpoptMpcc(const FormulationConfig& config);

}  // namespace cb
