// KLU's full numeric factorisation (klu_factor) of a large matrix, interruptible. KLU has no
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

// Matrices with fewer stored entries are factorised on the calling thread (a thread costs
// ~0.1 ms; such a factorisation takes well under a second).
constexpr Eigen::Index kInterruptibleKluMinNonZeros = 200000;

// The worker thread's name (at most 15 characters).
constexpr const char* kInterruptibleKluThreadName = "klu-factor";

// klu_factor(a, *symbolic, common). On an interrupt, returns null with *interrupted set and
// *symbolic null (the worker owns it now; the caller analyses again before the next
// factorisation); otherwise KLU's result, with *common holding KLU's status of it.
klu_numeric* FactorInterruptibly(const SpMat& a, klu_symbolic** symbolic, klu_common* common,
                                 bool* interrupted);

}  // namespace cb

#endif
