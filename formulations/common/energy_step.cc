#include "formulations/common/energy_step.h"

namespace cb {

bool IsEnergyStep(const std::string& formulation, const StepProblem& step, std::string* why) {
  if (step.constraint.kind != ConstraintKind::kFixedLoad) {
    *why = formulation + " cannot express the step constraint '" + ToString(step.constraint.kind) +
           "'";
    return false;
  }
  if (!step.model->has_energy()) {
    *why = formulation +
           ": the model has no energy (has_energy() is false: its internal force is not a "
           "gradient), so the step cannot be posed as energy minimisation; use an MPCC or an "
           "equation formulation";
    return false;
  }
  return true;
}

}  // namespace cb
