// The user's PETSc options that PETSc never read: a misspelling (-snes_monitr), an option of an
// object the formulation does not make, or one PETSc only reads at start-up (-log_view, -help).
// PETSc reads most options lazily, when it sets up the objects during the first solve, so the
// check runs after that solve; an option still unread then would never act, and a run that
// recorded it as applied would say more than what happened (issue 30).
#pragma once

#include <string>
#include <vector>

namespace cb {

// The option names ("-snes_monitr") of `user_options` (PETSc's syntax: names begin with '-'
// and a letter; anything else is a value) that PETSc holds, under `prefix`, as never used.
std::vector<std::string> UnusedPetscOptions(const std::string& prefix,
                                            const std::string& user_options);

// Throws std::invalid_argument listing UnusedPetscOptions when there are any.
void RefuseUnusedPetscOptions(const std::string& prefix, const std::string& user_options);

}  // namespace cb
