// KLU's symbolic analysis (klu_analyze), full numeric factorisation (klu_factor) and
// refactorisation in the last pivot order (klu_refactor, as slow as klu_factor on a 3-D system's
// fill) of a large matrix, interruptible. KLU has no
// hook to stop it, and on a 3-D system it can take minutes (hertz-3d with E >= 1e20 falls back
// from the condensed Cholesky to KLU at ~90 s a factorisation, and a SIGTERM took 73 s to act;
// issue 30). So the factorisation runs on a worker thread the caller can abandon
// (core/abandonable_work.h), which owns everything it touches: a copy of the matrix's arrays,
// the symbolic analysis (handed over), a copy of KLU's settings.
#pragma once

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <klu.h>

#include "core/sparse.h"

namespace cb {

// The worker threads' names (at most 15 characters).
constexpr const char* kInterruptibleKluThreadName = "klu-factor";
constexpr const char* kInterruptibleKluAnalysisThreadName = "klu-analyse";
constexpr const char* kInterruptibleKluRefactorThreadName = "klu-refactor";

// klu_analyze of a's pattern. On an interrupt, returns null with *interrupted set; otherwise
// KLU's result, with *common holding KLU's status of it.
klu_symbolic* AnalyseInterruptibly(const SpMat& a, klu_common* common, bool* interrupted);

// klu_refactor(a, *symbolic, *numeric, common): true when KLU returned success. On an interrupt,
// returns false with *interrupted set and *symbolic and *numeric null (the worker owns them now;
// the caller analyses again before the next factorisation).
bool RefactorInterruptibly(const SpMat& a, klu_symbolic** symbolic, klu_numeric** numeric,
                           klu_common* common, bool* interrupted);

// klu_factor(a, *symbolic, common). On an interrupt, returns null with *interrupted set and
// *symbolic null (the worker owns it now; the caller analyses again before the next
// factorisation); otherwise KLU's result, with *common holding KLU's status of it.
klu_numeric* FactorInterruptibly(const SpMat& a, klu_symbolic** symbolic, klu_common* common,
                                 bool* interrupted);

}  // namespace cb

#endif
