#include "harness/run_inputs.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/csv.h"
#include "core/owned_file.h"
#include "harness/options.h"
#include "harness/sha256.h"
#include "io/problem_file.h"

namespace cb::harness {

namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const fs::path& file, const std::string& role) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) {
    throw InputError("--problem-file: cannot read the " + role + " '" + file.string() + "'");
  }
  if (!in.is_open()) {
    throw InputError("--problem-file: cannot open the " + role + " '" + file.string() + "'");
  }
  return bytes;
}

void WriteBytes(const fs::path& file, const std::string& bytes) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw InputError("--out: cannot write the copy '" + file.string() + "': " + ec.message());
  try {
    WriteOwnedFile(file.string(), bytes, FileCreation::kReplace);  // never through a link
  } catch (const WriteError& e) {
    throw InputError("--out: the copy of an input: " + std::string(e.what()));
  }
}

// Where a mesh named `named` is copied, relative to the copies' directory: its own relative
// path when that stays inside, else its name alone (CopiedInput::found_by_copy false).
fs::path MeshCopy(const std::string& named, bool* found_by_copy) {
  const fs::path relative = fs::path(named).lexically_normal();
  *found_by_copy = relative.is_relative() && !relative.empty() && *relative.begin() != "..";
  return *found_by_copy ? relative : relative.filename();
}

CopiedInput Copy(const std::string& role, const fs::path& source, const fs::path& copy,
                 const std::string& out, bool found_by_copy, std::string* bytes) {
  *bytes = ReadBytes(source, role);
  const fs::path relative = fs::path(kInputsDirectory) / copy;
  WriteBytes(fs::path(out) / relative, *bytes);
  return {role, source.string(), relative.generic_string(), Sha256Hex(*bytes), found_by_copy};
}

}  // namespace

std::vector<CopiedInput> CopyProblemInputs(const std::string& problem_file,
                                           const std::string& out) {
  std::vector<CopiedInput> copies;
  std::string text;
  const fs::path source(problem_file);
  copies.push_back(Copy("problem file", source, source.filename(), out, true, &text));
  for (const std::string& named : io::ReferencedFiles(text)) {
    bool found_by_copy = true;
    const fs::path copy = MeshCopy(named, &found_by_copy);
    std::string bytes;
    copies.push_back(Copy("mesh", (source.parent_path() / named).lexically_normal(), copy, out,
                          found_by_copy, &bytes));
  }
  return copies;
}

}  // namespace cb::harness
