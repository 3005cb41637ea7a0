// A problem traced as `contactbench run` traces it, for programs that use the library: the path
// options with the suite's defaults for this problem, and the run of its loading (the
// fixed-load solve, or the arc-length path), so that the library and the command line agree.
#pragma once

#include "path/path.h"
#include "problems/problem.h"

namespace cb {

// What `contactbench run` detects by default: limit and bifurcation points are recorded.
constexpr BifurcationMode kDefaultBifurcationMode = BifurcationMode::kDetect;

// PathOptions' defaults with the problem's own arc length (theta of (33)) and step count, and
// kDefaultBifurcationMode: the options of `contactbench run` given no option.
PathOptions DefaultPathOptions(const Problem& problem);

// The problem's first step as the formulation is asked to accept it (Formulation::Accepts):
// the fixed load, or an arc-length step of `options`.
StepProblem FirstStep(const Problem& problem, const PathOptions& options);

// Runs the problem's loading from the unloaded state with `formulation`: the fixed-load solve
// (SolveFixedLoad, from `guess` when given) or the arc-length path (TraceArcLengthPath).
PathSummary TraceProblem(const Problem& problem, Formulation& formulation,
                         const PathOptions& options, PathObserver* observer = nullptr,
                         const State* guess = nullptr);

}  // namespace cb
