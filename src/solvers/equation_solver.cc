#include "solvers/equation_solver.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "solvers/dogleg.h"
#include "solvers/linear_solver.h"
#include "solvers/newton.h"
#include "solvers/quasi_newton.h"

namespace cb {
namespace {

std::string JoinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) {
    if (!joined.empty()) joined += ", ";
    joined += name;
  }
  return joined;
}

// Sets *why (when given) and returns false; keeps IsValid a flat list of checks.
bool Invalid(std::string* why, const std::string& reason) {
  if (why != nullptr) *why = reason;
  return false;
}

}  // namespace

bool SolverOptions::IsValid(std::string* why) const {
  // Written as !(x > 0) so that NaN is rejected too.
  if (!(residual_tol > 0.0)) {
    return Invalid(why, "residual_tol must be positive, got " + std::to_string(residual_tol));
  }
  if (max_iterations < 1) {
    return Invalid(why, "max_iterations must be >= 1, got " + std::to_string(max_iterations));
  }
  if (!(step_tol > 0.0)) {
    return Invalid(why, "step_tol must be positive, got " + std::to_string(step_tol));
  }
  if (!(armijo > 0.0 && armijo < 0.5)) {
    return Invalid(why, "armijo must lie in (0, 0.5), got " + std::to_string(armijo));
  }
  if (max_backtracks < 1) {
    return Invalid(why, "max_backtracks must be >= 1, got " + std::to_string(max_backtracks));
  }
  if (nonmonotone_window < 1) {
    return Invalid(why,
                   "nonmonotone_window must be >= 1, got " + std::to_string(nonmonotone_window));
  }
  if (!(backtrack_min > 0.0)) {
    return Invalid(why, "backtrack_min must be positive, got " + std::to_string(backtrack_min));
  }
  if (!(backtrack_max < 1.0)) {
    return Invalid(why, "backtrack_max must be < 1, got " + std::to_string(backtrack_max));
  }
  if (!(backtrack_min <= backtrack_max)) {
    return Invalid(why, "backtrack_min (" + std::to_string(backtrack_min) +
                            ") must not exceed backtrack_max (" + std::to_string(backtrack_max) +
                            ")");
  }
  if (!(initial_radius_factor > 0.0)) {
    return Invalid(why, "initial_radius_factor must be positive, got " +
                            std::to_string(initial_radius_factor));
  }
  // Above 0.25 a step could be accepted while the radius shrinks for it; below 0 a step that
  // increases m would be accepted.
  if (!(accept_ratio >= 0.0 && accept_ratio < 0.25)) {
    return Invalid(why, "accept_ratio must lie in [0, 0.25), got " + std::to_string(accept_ratio));
  }
  if (max_updates < 1) {
    return Invalid(why, "max_updates must be >= 1, got " + std::to_string(max_updates));
  }
  const std::vector<std::string> linear = LinearSolverNames();
  if (std::find(linear.begin(), linear.end(), linear_solver) == linear.end()) {
    return Invalid(why,
                   "linear_solver '" + linear_solver + "' is not one of: " + JoinNames(linear));
  }
  return true;
}

std::vector<std::string> EquationSolverNames() { return {"newton", "dogleg", "quasi-newton"}; }

std::unique_ptr<EquationSolver> MakeEquationSolver(const std::string& name,
                                                   const SolverOptions& options) {
  const std::vector<std::string> names = EquationSolverNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw std::invalid_argument("unknown equation solver '" + name +
                                "'; valid names: " + JoinNames(names));
  }
  std::string why;
  if (!options.IsValid(&why)) {
    throw std::invalid_argument("invalid SolverOptions for '" + name + "': " + why);
  }
  if (name == "newton") return std::make_unique<NewtonSolver>(options);
  if (name == "dogleg") return std::make_unique<DoglegSolver>(options);
  return std::make_unique<QuasiNewtonSolver>(options);
}

}  // namespace cb
