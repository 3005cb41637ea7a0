// Which problem files are FCLIB files: decided by name in every build, so that a build without
// HDF5 still recognises one and refuses it with the reason (src/io/fclib/fclib_stub.cc).
#include <filesystem>

#include "io/fclib_file.h"

namespace cb::io {

bool IsFclibPath(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".hdf5" || extension == ".h5";
}

}  // namespace cb::io
