// The problem-file reader's entry points (io/problem_file.h): the JSON parsed, its "kind"
// picks the reader (problem_file_kinds.h), and the fields every kind shares ("name", "units").
#include <filesystem>
#include <nlohmann/json.hpp>

#include "io/fclib_file.h"
#include "io/input_file.h"
#include "io/json_node.h"
#include "io/problem_file.h"
#include "io/problem_file_kinds.h"
#include "io/problem_file_loading.h"
#include "io/problem_name.h"

namespace cb::io {

Problem ParseProblemFile(const std::string& text, const std::string& file,
                         const std::string& directory,
                         const std::map<std::string, std::string>& settings) {
  const Json json = ParseJson(text, file);
  const JsonNode root(&json, file, "");
  if (!json.is_object()) root.Fail("a problem file is a JSON object");
  reading::ReadVersion(root);
  const JsonNode kind = root.Field("kind");
  const std::string k = kind.String();
  Problem problem;
  if (k == "truss") {
    problem = reading::ReadTruss(root, file, settings);
  } else if (k == "plane-stress-q4") {
    problem = reading::ReadPlaneStress(root, file, directory, settings);
  } else if (k == "solid-hex8") {
    problem = reading::ReadSolidHex8(root, file, directory, settings);
  } else if (k == "lcp") {
    problem = reading::ReadLcp(root, file, settings);
  } else {
    kind.Fail("must be \"truss\", \"plane-stress-q4\", \"solid-hex8\" or \"lcp\", got \"" + k +
              "\"");
  }
  problem.name = reading::OptionalString(root, "name", std::filesystem::path(file).stem().string());
  if (problem.name.empty()) root.Field("name").Fail("must not be empty");
  if (!IsFileSafeName(problem.name)) {
    throw InputError(file, "/name",
                     "'" + problem.name +
                         "' cannot name the output files (vtk/NAME.pvd): use letters, digits "
                         "and ._+- only, not first '.' or '-'" +
                         (root.Has("name") ? "" : "; the default is the file's name"));
  }
  problem.units = reading::OptionalString(root, "units", k == "lcp" ? "none" : "consistent units");
  return problem;
}

Problem LoadProblemFile(const std::string& path, const std::map<std::string, std::string>& settings,
                        std::uintmax_t max_bytes) {
  if (IsFclibPath(path)) return LoadFclibFile(path, settings);
  const std::string text = ReadInputFile(path, "problem file", max_bytes, "--allow-memory");
  const std::string directory = std::filesystem::path(path).parent_path().string();
  return ParseProblemFile(text, path, directory.empty() ? "." : directory, settings);
}

std::vector<std::string> ReferencedFiles(const std::string& text) {
  const auto root = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!root.is_object()) return {};
  const auto mesh = root.find("mesh");
  if (mesh == root.end() || !mesh->is_object()) return {};
  const auto file = mesh->find("file");
  if (file == mesh->end() || !file->is_string()) return {};
  return {file->get<std::string>()};
}

}  // namespace cb::io
