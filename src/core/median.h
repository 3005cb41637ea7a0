// The median of a sample: the comparison table's median iterations and times, and the time a
// repeated solve records (path/step_solve.h).
#pragma once

#include <vector>

namespace cb {

// The median of `values` (the mean of the two middle ones for an even count); nan when empty.
double Median(std::vector<double> values);

}  // namespace cb
