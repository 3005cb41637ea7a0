// FCLIB files in a build without HDF5 (libhdf5-dev absent when CMake ran): every entry point
// refuses with the reason, so a user learns what to install instead of reading a parse error.
#include "io/fclib_file.h"
#include "io/input_error.h"

namespace cb::io {

namespace {

[[noreturn]] void Unavailable(const std::string& path) {
  throw InputError(path, "",
                   "FCLIB files need HDF5, and this build has none: install libhdf5-dev "
                   "(scripts/packages.txt) and configure again");
}

}  // namespace

bool FclibAvailable() { return false; }

Problem LoadFclibFile(const std::string& path, const std::map<std::string, std::string>&) {
  Unavailable(path);
}

FclibAnswers LoadFclibAnswers(const std::string& path) { Unavailable(path); }

void WriteFclibFile(const Problem&, const std::string& path, const FclibState*, const FclibState*) {
  Unavailable(path);
}

}  // namespace cb::io
