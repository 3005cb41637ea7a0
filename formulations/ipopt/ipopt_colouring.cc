#include "formulations/ipopt/ipopt_colouring.h"

#include <algorithm>

namespace cb {

int ColourColumns(const SpMat& pattern, std::vector<int>* colour) {
  const int n = static_cast<int>(pattern.cols());
  colour->assign(n, -1);
  int num_colours = 0;
  std::vector<int> mark(n + 1, -1);
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  for (int j = 0; j < n; ++j) {
    for (int a = outer[j]; a < outer[j + 1]; ++a) {
      const int i = inner[a];  // row i of column j; by symmetry column i lists row i's columns
      for (int b = outer[i]; b < outer[i + 1]; ++b) {
        const int c = (*colour)[inner[b]];
        if (c >= 0) mark[c] = j;
      }
    }
    int c = 0;
    while (mark[c] == j) ++c;
    (*colour)[j] = c;
    num_colours = std::max(num_colours, c + 1);
  }
  return num_colours;
}

}  // namespace cb
