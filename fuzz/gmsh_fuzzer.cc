// libFuzzer target: the Gmsh 4.1 mesh reader (src/io/gmsh.cc). Built and run by
// scripts/run_fuzz.sh.
#include "readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cb::fuzz::GmshInput(data, size);
  return 0;
}
