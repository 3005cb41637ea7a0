// NLopt renderings of a step (issue 3): `nlopt-merit` (1/2 ||F||^2 of the implicit smoothed-FB
// system), `nlopt-energy` (fixed-load energy NLP) and `nlopt-mpcc` (penalty-form step NLP).
#pragma once

#include <memory>

#include "formulations/config.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has NLopt (CONTACTBENCH_HAVE_NLOPT).
bool NloptAvailable();
std::unique_ptr<Formulation> MakeNloptMerit(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeNloptEnergy(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeNloptMpcc(const FormulationConfig& config);

}  // namespace cb
