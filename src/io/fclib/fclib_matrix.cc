#include "io/fclib/fclib_matrix.h"

#include <climits>
#include <cmath>
#include <vector>

#include "io/input_error.h"

namespace cb::io {

namespace {

// The most entries a matrix may declare: an int index, as FCLIB stores them.
constexpr long long kMaxEntries = INT_MAX;

long long Dimension(const Hdf5File& file, const std::string& path, long long min) {
  const long long v = file.Integer(path);
  if (v < min || v > kMaxEntries) {
    throw InputError(file.name(), path,
                     "must be in " + std::to_string(min) + ".." + std::to_string(kMaxEntries) +
                         ", got " + std::to_string(v));
  }
  return v;
}

// `count` entries of the dataset at `path` (which may hold more, up to nzmax).
template <typename T>
std::vector<T> Leading(std::vector<T> values, std::size_t count, const Hdf5File& file,
                       const std::string& path) {
  if (values.size() < count) {
    throw InputError(
        file.name(), path,
        "has " + std::to_string(values.size()) + " entries, needs " + std::to_string(count));
  }
  values.resize(count);
  return values;
}

void CheckIndex(long long index, long long bound, const Hdf5File& file, const std::string& path,
                std::size_t k) {
  if (index < 0 || index >= bound) {
    throw InputError(file.name(), path + "[" + std::to_string(k) + "]",
                     std::to_string(index) + " outside 0.." + std::to_string(bound - 1));
  }
}

// Compressed storage: `starts` (size outer + 1, from 0, non-decreasing, ending at the count)
// and `indices` (inner indices).
std::vector<Triplet> Compressed(const Hdf5File& file, const std::string& group, long long outer,
                                long long inner, long long nzmax, bool columns) {
  const auto starts =
      Leading(file.Integers(group + "/p", outer + 1), outer + 1, file, group + "/p");
  if (starts[0] != 0) throw InputError(file.name(), group + "/p[0]", "must be 0");
  for (long long k = 0; k < outer; ++k) {
    if (starts[k + 1] < starts[k]) {
      throw InputError(file.name(), group + "/p[" + std::to_string(k + 1) + "]",
                       "pointers must not decrease");
    }
  }
  const long long count = starts[outer];
  if (count > nzmax) {
    throw InputError(
        file.name(), group + "/p[" + std::to_string(outer) + "]",
        std::to_string(count) + " entries, more than nzmax = " + std::to_string(nzmax));
  }
  const auto indices = Leading(file.Integers(group + "/i", nzmax), count, file, group + "/i");
  const auto values = Leading(file.Reals(group + "/x", nzmax), count, file, group + "/x");
  std::vector<Triplet> triplets;
  triplets.reserve(count);
  for (long long o = 0; o < outer; ++o) {
    for (long long k = starts[o]; k < starts[o + 1]; ++k) {
      CheckIndex(indices[k], inner, file, group + "/i", k);
      const int a = static_cast<int>(indices[k]);
      const int b = static_cast<int>(o);
      triplets.emplace_back(columns ? a : b, columns ? b : a, values[k]);
    }
  }
  return triplets;
}

std::vector<Triplet> Triplets(const Hdf5File& file, const std::string& group, long long rows,
                              long long cols, long long nz) {
  const auto row = Leading(file.Integers(group + "/i", nz), nz, file, group + "/i");
  const auto col = Leading(file.Integers(group + "/p", nz), nz, file, group + "/p");
  const auto values = Leading(file.Reals(group + "/x", kMaxEntries), nz, file, group + "/x");
  std::vector<Triplet> triplets;
  triplets.reserve(nz);
  for (long long k = 0; k < nz; ++k) {
    CheckIndex(row[k], rows, file, group + "/i", k);
    CheckIndex(col[k], cols, file, group + "/p", k);
    triplets.emplace_back(static_cast<int>(row[k]), static_cast<int>(col[k]), values[k]);
  }
  return triplets;
}

}  // namespace

SpMat ReadFclibMatrix(const Hdf5File& file, const std::string& group) {
  const long long rows = Dimension(file, group + "/m", 1);
  const long long cols = Dimension(file, group + "/n", 1);
  const long long nzmax = Dimension(file, group + "/nzmax", 0);
  const long long nz = file.Integer(group + "/nz");
  std::vector<Triplet> triplets;
  if (nz >= 0) {
    if (nz > kMaxEntries) throw InputError(file.name(), group + "/nz", "too large");
    triplets = Triplets(file, group, rows, cols, nz);
  } else if (nz == -1) {
    triplets = Compressed(file, group, cols, rows, nzmax, true);
  } else if (nz == -2) {
    triplets = Compressed(file, group, rows, cols, nzmax, false);
  } else {
    throw InputError(file.name(), group + "/nz",
                     "must be >= 0 (triplets), -1 (compressed columns) or -2 (compressed rows), "
                     "got " +
                         std::to_string(nz));
  }
  for (std::size_t k = 0; k < triplets.size(); ++k) {
    if (!std::isfinite(triplets[k].value())) {
      throw InputError(file.name(), group + "/x[" + std::to_string(k) + "]", "not finite");
    }
  }
  SpMat matrix(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  matrix.makeCompressed();
  return matrix;
}

void WriteFclibMatrix(const Hdf5File& file, const std::string& group, const SpMat& matrix) {
  SpMat m = matrix;
  m.makeCompressed();
  file.MakeGroup(group);
  const int nnz = static_cast<int>(m.nonZeros());
  file.WriteIntegers(group + "/nzmax", {nnz});
  file.WriteIntegers(group + "/m", {static_cast<int>(m.rows())});
  file.WriteIntegers(group + "/n", {static_cast<int>(m.cols())});
  file.WriteIntegers(group + "/nz", {-1});
  file.WriteIntegers(group + "/p",
                     std::vector<int>(m.outerIndexPtr(), m.outerIndexPtr() + m.cols() + 1));
  file.WriteIntegers(group + "/i", std::vector<int>(m.innerIndexPtr(), m.innerIndexPtr() + nnz));
  file.WriteReals(group + "/x", m.valuePtr(), static_cast<std::size_t>(nnz));
}

}  // namespace cb::io
