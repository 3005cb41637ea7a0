// CHOLMOD's symbolic analysis (cholmod_analyze: the ordering, seconds on a large 3-D pattern)
// and numeric factorisation (cholmod_factorize) of a large matrix, interruptible. CHOLMOD
// has no hook to stop it, and on a 3-D system its supernodal factorisation can take tens of
// seconds (hertz-3d with E >= 1e20: 18-36 s an iteration before the fall-back to KLU, and a
// SIGTERM waited for it; issue 30). So the factorisation runs on a worker thread the caller can
// abandon (core/abandonable_work.h, as KLU's: interruptible_klu.h), which owns everything it
// touches: a copy of the matrix's arrays, the factor (handed over) and a cholmod_common of its
// own with the same settings (cholmod_wrappers.h). A finished factor is handed back; CHOLMOD's
// memory counters then credit its storage to the worker's common, which only CHOLMOD's
// statistics read.
#pragma once

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include "core/sparse.h"
#include "solvers/cholmod_wrappers.h"

namespace cb {

// The worker threads' names (at most 15 characters).
constexpr const char* kInterruptibleCholmodThreadName = "cholmod-factor";
constexpr const char* kInterruptibleCholmodAnalysisThreadName = "cholmod-analyse";

// cholmod->Analyse(view of *lower), or cholmod->AnalyseInOrder(view, permutation) when
// `permutation` is given (d entries; copied). On an interrupt, returns an empty factor with
// *interrupted set; the worker frees what it made.
CholmodFactor AnalyseInterruptibly(Cholmod* cholmod, SpMat* lower, const int* permutation,
                                   bool* interrupted);

// cholmod->Factorize(view of *lower, *factor): *lower stores the lower triangle of a symmetric
// matrix with the pattern *factor was analysed for (CHOLMOD only reads it). On an interrupt,
// returns false with *interrupted set and *factor empty (the worker owns it now; the caller
// analyses again before the next factorisation); otherwise Cholmod::Factorize's answer.
bool FactorizeInterruptibly(Cholmod* cholmod, SpMat* lower, CholmodFactor* factor,
                            bool* interrupted);

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
