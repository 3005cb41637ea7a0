#include "formulations/petsc/petsc_unused_options.h"

#include <petscsys.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

namespace cb {

namespace {

// The option names of `options`, without their '-' ("snes_monitr").
std::vector<std::string> OptionNames(const std::string& options) {
  std::vector<std::string> names;
  std::istringstream words(options);
  std::string word;
  while (words >> word) {
    if (word.size() > 1 && word[0] == '-' && std::isalpha(static_cast<unsigned char>(word[1]))) {
      names.push_back(word.substr(1));
    }
  }
  return names;
}

// Whether PETSc's stored name `stored` ("cb1_snes_monitr") is `prefix` + `name`, compared
// without case as PETSc compares option names.
bool SameOption(const std::string& stored, const std::string& prefix, const std::string& name) {
  const std::string full = prefix + name;
  return stored.size() == full.size() &&
         std::equal(stored.begin(), stored.end(), full.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) ==
                  std::tolower(static_cast<unsigned char>(b));
         });
}

}  // namespace

std::vector<std::string> UnusedPetscOptions(const std::string& prefix,
                                            const std::string& user_options) {
  const std::vector<std::string> names = OptionNames(user_options);
  std::vector<std::string> unused;
  if (names.empty()) return unused;
  PetscInt count = 0;
  char** stored = nullptr;
  char** values = nullptr;
  if (PetscOptionsLeftGet(nullptr, &count, &stored, &values) != 0) return unused;
  for (PetscInt i = 0; i < count; ++i) {
    for (const std::string& name : names) {
      if (SameOption(stored[i], prefix, name) &&
          std::find(unused.begin(), unused.end(), "-" + name) == unused.end()) {
        unused.push_back("-" + name);
      }
    }
  }
  PetscOptionsLeftRestore(nullptr, &count, &stored, &values);
  return unused;
}

void RefuseUnusedPetscOptions(const std::string& prefix, const std::string& user_options) {
  const std::vector<std::string> unused = UnusedPetscOptions(prefix, user_options);
  if (unused.empty()) return;
  std::string list;
  for (const std::string& name : unused) list += (list.empty() ? "" : ", ") + name;
  throw std::invalid_argument(
      "--petsc-options: PETSc did not use " + list +
      " in the first solve (misspelt, not an option of this solver, or "
      "read only at PETSc's start-up); the run stops at its first solve rather than record "
      "options that did nothing");
}

}  // namespace cb
