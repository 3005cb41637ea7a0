// The column colouring of MpccNlp's finite-difference Hessian term (ipopt_nlp.h).
#pragma once

#include <vector>

#include "core/types.h"

namespace cb {

// Greedy distance-2 colouring of the columns of a structurally symmetric pattern: two columns
// share a colour only when no row has entries in both, so one central difference serves them
// all (Curtis, Powell and Reid). *colour gets one colour per column, in column order; returns
// the number of colours.
int ColourColumns(const SpMat& pattern, std::vector<int>* colour);

}  // namespace cb
