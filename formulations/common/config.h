// Settings handed to a formulation by the registry. Backend-specific settings travel as
// KEY=VALUE strings (CLI: --option KEY=VALUE); each formulation reads its own through an
// OptionReader and refuses any key it does not know.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "solvers/equation_solver.h"

namespace cb {

struct FormulationConfig {
  std::string solver = "newton";  // equation solver (implicit-fb, nonsmooth-fb, active-set)
  int eta = 1;                    // eta case 1..4 (implicit-fb)
  SolverOptions solver_options;   // equation solvers' options (tolerances, linear solver)
  std::map<std::string, std::string> options;  // backend-specific KEY=VALUE
};

// Typed access to FormulationConfig::options. Every Get* records the key as known; Finish()
// throws std::invalid_argument naming any key that was given but never read, with the list of
// known ones. Bad values throw std::invalid_argument naming the key.
class OptionReader {
 public:
  OptionReader(std::string formulation, const std::map<std::string, std::string>& options);
  double GetReal(const std::string& key, double fallback);
  int GetInteger(const std::string& key, int fallback);
  std::string GetChoice(const std::string& key, const std::string& fallback,
                        const std::vector<std::string>& choices);
  bool GetBool(const std::string& key, bool fallback);
  void Finish() const;

 private:
  const std::string* Find(const std::string& key);
  std::string formulation_;
  const std::map<std::string, std::string>& options_;
  std::set<std::string> known_;
};

}  // namespace cb
