// Events the library reports for the program to show, since nothing in the library prints: a
// piece of work about to start that will cost minutes, such as the condensed Cholesky's fall-back
// to KLU on the whole Jacobian of a large 3-D system (~90 s a factorisation; issue 30). The
// program installs a listener (the harness's progress line); without one the events go nowhere.
#pragma once

#include <cstdint>
#include <string>

namespace cb {

// A fall-back of one linear solver to another on a large matrix (the factorisations that run on
// an abandonable worker: solvers/interruptible_klu.h). Whether it costs minutes depends on the
// fill, which the library does not know before factorising; the program judges it.
struct SlowWork {
  std::string from, to;   // the solvers, e.g. "cholmod" and "klu"
  std::int64_t rows = 0;  // the matrix the fall-back factorises
  std::int64_t nonzeros = 0;
};

// Called on the thread that reports, before the work starts.
using SlowWorkListener = void (*)(const SlowWork&);

void SetSlowWorkListener(SlowWorkListener listener);

// Hands `work` to the installed listener, if any.
void ReportSlowWork(const SlowWork& work);

}  // namespace cb
