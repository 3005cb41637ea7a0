// One input of the reader fuzzers (fuzz/*_fuzzer.cc) and of their regression test
// (tests/fuzz_regressions_test.cc): the bytes are handed to a reader as a file's contents.
// The readers' contract is that bad input is refused with std::invalid_argument (io::InputError,
// the CLI's exit status 2); anything else escaping (another exception, a crash, a sanitizer
// report, a hang, an allocation beyond the fuzzer's limit) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "io/gmsh.h"
#include "io/problem_file.h"

namespace cb::fuzz {

// A mesh file named by a problem file is looked up in `directory` (the fuzzers and the test pass
// examples/, so "q4-block-gmsh.msh" resolves). Inputs naming a file outside it (an absolute
// path, "..") are skipped: reading /dev/zero or a FIFO would only test the operating system.
inline bool NamesOutsideFile(const std::string& text) {
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!json.is_object()) return false;
  const auto mesh = json.find("mesh");
  if (mesh == json.end() || !mesh->is_object()) return false;
  const auto file = mesh->find("file");
  if (file == mesh->end() || !file->is_string()) return false;
  const std::string name = file->get<std::string>();
  return name.empty() || name[0] == '/' || name.find("..") != std::string::npos;
}

inline void ProblemFileInput(const std::uint8_t* data, std::size_t size,
                             const std::string& directory) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (NamesOutsideFile(text)) return;
  try {
    const Problem problem = io::ParseProblemFile(text, "fuzz.json", directory);
    // What a run does first with a problem: its sizes and the load pattern.
    (void)problem.model->num_dofs();
    (void)problem.model->load_pattern().size();
  } catch (const std::invalid_argument&) {
    // Refused with a reason: the contract.
  }
}

inline void GmshInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)io::ParseGmsh(text, "fuzz.msh");
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace cb::fuzz
