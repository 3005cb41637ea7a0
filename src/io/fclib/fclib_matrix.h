// An FCLIB sparse matrix (a group with nzmax, m, n, nz, p, i, x) read into an SpMat with every
// index checked, in the three storages FCLIB has: nz >= 0 triplets, nz = -1 compressed columns,
// nz = -2 compressed rows. In triplet form `i` holds the row indices and `p` the column indices,
// the opposite of fclib.h's comment: that is how FCLIB's own writer and the LMGC90 and Siconos
// files store them (docs/problem-files.md). Repeated triplets are summed, as CSparse does.
#pragma once

#include <string>

#include "core/types.h"
#include "io/fclib/hdf5_file.h"

namespace cb::io {

SpMat ReadFclibMatrix(const Hdf5File& file, const std::string& group);

// Writes `matrix` under `group` (created) in compressed-column form (nz = -1), as FCLIB's
// writer does for a CSparse matrix.
void WriteFclibMatrix(const Hdf5File& file, const std::string& group, const SpMat& matrix);

}  // namespace cb::io
