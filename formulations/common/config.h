// Settings handed to a formulation by the registry. Backend-specific settings travel as
// KEY=VALUE strings (CLI: --option KEY=VALUE); each formulation reads its own through an
// OptionReader and refuses any key it does not know.
#pragma once

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "parallel/element_split.h"
#include "solvers/equation_solver.h"

namespace cb {

struct FormulationConfig {
  std::string solver = "newton";  // equation solver (implicit-fb, nonsmooth-fb, active-set)
  int eta = 1;                    // eta case 1..4 (implicit-fb)
  SolverOptions solver_options;   // equation solvers' options (tolerances, linear solver)
  std::map<std::string, std::string> options;  // backend-specific KEY=VALUE
  // Where a distributed formulation records how it split the body's elements over the
  // processes (parallel/element_split.h); owned by the run, which outlives the formulation; none
  // outside a run.
  ElementSplit* element_split = nullptr;
};

// A key no reader of a formulation's options knows: the message lists the known keys, which
// `known` holds for a caller that suggests the closest.
class UnknownOptionError : public std::invalid_argument {
 public:
  UnknownOptionError(const std::string& message, std::string key, std::vector<std::string> known)
      : std::invalid_argument(message), key_(std::move(key)), known_(std::move(known)) {}
  const std::string& key() const { return key_; }
  const std::vector<std::string>& known() const { return known_; }

 private:
  std::string key_;
  std::vector<std::string> known_;
};

// Typed access to FormulationConfig::options. Every Get* records the key as known; Finish()
// throws UnknownOptionError naming any key that was given but never read, with the list of
// known ones. Bad values throw std::invalid_argument naming the key.
class OptionReader {
 public:
  OptionReader(std::string formulation, const std::map<std::string, std::string>& options);
  double GetReal(const std::string& key, double fallback);
  int GetInteger(const std::string& key, int fallback);
  std::string GetChoice(const std::string& key, const std::string& fallback,
                        const std::vector<std::string>& choices);
  bool GetBool(const std::string& key, bool fallback);
  // Free text passed through as given (a library's own option syntax).
  std::string GetText(const std::string& key, const std::string& fallback);
  void Finish() const;

 private:
  const std::string* Find(const std::string& key);
  std::string formulation_;
  const std::map<std::string, std::string>& options_;
  std::set<std::string> known_;
};

}  // namespace cb
