// The files a run read, kept in its --out: a problem file and the meshes it names are copied
// into DIR/problem/ and fingerprinted (SHA-256), so that run.json says exactly what was solved
// and `contactbench rerun` can solve it again from the copies.
#pragma once

#include <string>
#include <vector>

namespace cb::harness {

struct CopiedInput {
  std::string role;    // "problem file" or "mesh"
  std::string source;  // where the run read it
  std::string copy;    // the copy, relative to --out ("problem/q4.json")
  std::string sha256;  // of the content read (sha256.h)
  // The copy sits where the copied problem file looks for it: a mesh named by a relative path
  // that stays in the problem file's directory. A mesh named by an absolute path or one
  // outside (../m.msh) is copied by its name alone, and the copied problem file would not read
  // it: `rerun` refuses such a run unless forced.
  bool found_by_copy = true;
};

// The directory under --out that holds the copies.
inline constexpr const char* kInputsDirectory = "problem";

// Copies `problem_file` and the files it names (io::ReferencedFiles) into OUT/problem/; throws
// InputError naming the file when one cannot be read or written.
std::vector<CopiedInput> CopyProblemInputs(const std::string& problem_file, const std::string& out);

}  // namespace cb::harness
