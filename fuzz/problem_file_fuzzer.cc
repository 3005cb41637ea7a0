// libFuzzer target: problem files (src/io/problem_file_reader.cc, json_node.cc, and through a
// "mesh" field the Gmsh reader). Built and run by scripts/run_fuzz.sh.
#include "readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cb::fuzz::ProblemFileInput(data, size, CONTACTBENCH_EXAMPLES_DIR);
  return 0;
}
