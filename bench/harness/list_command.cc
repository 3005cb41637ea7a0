#include <iostream>

#include "formulations/registry.h"
#include "harness/cli.h"
#include "harness/cli_commands.h"
#include "problems/problem.h"
#include "solvers/equation_solver.h"
#include "solvers/linear_solver.h"

namespace cb::harness {

int ListCommand() {
  std::cout << "problems:\n";
  for (const auto& info : ProblemRegistry()) {
    std::cout << "  " << info.name << "  " << info.description << "\n";
    // Hold the defaults: a range-for over a member of a temporary would dangle (before C++23).
    const Parameters defaults = info.defaults();
    for (const auto& e : defaults.entries()) {
      std::cout << "      " << e.name << " = " << e.value << "   " << e.doc << "\n";
    }
  }
  std::cout << "formulations:\n";
  for (const auto& info : FormulationRegistry()) {
    std::cout << "  " << info.name << (info.available ? "" : " (not built)") << "  "
              << info.description << "\n";
  }
  std::cout << "solvers (--solver):\n  " << Join(EquationSolverNames()) << "\n";
  std::cout << "linear solvers (--linear-solver):\n  " << Join(LinearSolverNames()) << "\n";
  return kExitOk;
}

}  // namespace cb::harness
