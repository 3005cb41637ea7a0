// What a step must be for the energy formulations (ipopt-energy, nlopt-energy) to pose it as
// minimising the model's energy,
//   min pi(u) - lambda f^T u   s.t.   phi(u) <= 0,
// whose KKT conditions are (9)-(11): a fixed-load step (lambda given; an arc-length,
// displacement or kink step has lambda or the contact variables as unknowns of its own row),
// of a model with an energy (ContactModel::has_energy: its internal force is the gradient of
// pi). The formulations answer Accepts with it, and their NLPs refuse other steps with it.
#pragma once

#include <string>

#include "step/step_problem.h"

namespace cb {

// Whether `step` can be posed as energy minimisation; otherwise false with the reason, naming
// `formulation`, in *why.
bool IsEnergyStep(const std::string& formulation, const StepProblem& step, std::string* why);

}  // namespace cb
