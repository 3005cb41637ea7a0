// A start near the solution of a fixed-load problem, as the report's section 5.1 starts eta
// case 3 (whose degenerate root converges only linearly, docs/method.md section 2) close to the
// solution: the fixed-load problem is solved once by a reference formulation, and its solution
// is perturbed by a small relative offset with a fixed pattern, so that runs are reproducible.
#pragma once

#include <string>

#include "path/path.h"

namespace cb {

// `solution` with every entry moved by the relative offset `delta`:
//   u_i (1 + delta sin(i + 1)),  r_i (1 + delta sin(i + 2)).
// A fixed pattern of mixed signs rather than random numbers, so that a run started from it can
// be repeated; no entry moves by more than delta of itself. lambda is kept.
State PerturbedSolution(const State& solution, double delta);

// Solves the fixed-load problem (the load parameter `lambda` from `initial`) with `reference`
// and returns in *start its solution perturbed by PerturbedSolution(., delta). Returns false
// with *why (the reference solve's message) when the reference solve does not converge.
bool NearSolutionStart(const ContactModel& model, const ContactScales& scales, const State& initial,
                       double lambda, Formulation& reference, const PathOptions& options,
                       double delta, State* start, std::string* why);

}  // namespace cb
