// The nonsmooth renderings of a step (issue 3): `nonsmooth-fb`, (29), (30), (33) with the plain
// Fischer-Burmeister function psi_FB(g, -r) solved by a semismooth Newton method, and
// `active-set`, the same with the min function (a primal-dual active-set method).
#pragma once

#include <memory>

#include "formulations/config.h"
#include "step/formulation.h"

namespace cb {

std::unique_ptr<Formulation> MakeNonsmoothFb(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeActiveSet(const FormulationConfig& config);

}  // namespace cb
