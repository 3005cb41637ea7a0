#include "harness/rerun.h"

#include <contactbench_build_info.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "core/blas_info.h"
#include "formulations/registry.h"
#include "harness/options.h"
#include "harness/run_json.h"
#include "harness/sha256.h"
#include "parallel/processes.h"

namespace cb::harness {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

[[noreturn]] void Refuse(const std::string& dir, const std::string& why) {
  throw InputError("rerun: '" + dir + "': " + why);
}

Json ReadRunJson(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) Refuse(dir, "no such directory");
  if (!fs::is_directory(dir, ec)) Refuse(dir, "not a directory");
  const fs::path file = fs::path(dir) / "run.json";
  if (!fs::exists(file, ec)) {
    Refuse(dir, "holds no run.json (give the --out directory of a run or a comparison)");
  }
  std::ifstream in(file);
  Json run = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (run.is_discarded() || !run.is_object()) Refuse(dir, "run.json is not a JSON object");
  return run;
}

// The recorded command line after the program's name, checked.
std::vector<std::string> RecordedCommandLine(const std::string& dir, const Json& run) {
  const auto line = run.find("command_line");
  bool strings = line != run.end() && line->is_array() && line->size() >= 2;
  if (strings) {
    for (const auto& item : *line) strings = strings && item.is_string();
  }
  if (!strings) Refuse(dir, "run.json: \"command_line\" is missing or not a list of strings");
  std::vector<std::string> words = line->get<std::vector<std::string>>();
  if (words[1] != "run" && words[1] != "compare") {
    Refuse(dir, "run.json: the command '" + words[1] + "' cannot be rerun (only run and compare)");
  }
  return {words.begin() + 1, words.end()};
}

// Whether option `name` takes a value (any command's entry of that name).
bool TakesValue(const std::string& name) {
  for (const Option& o : Options()) {
    if (name == o.name) return *o.placeholder != '\0';
  }
  return false;
}

// The recorded copy of the problem file, as a path under DIR ("" when the run had none).
std::string ProblemFileCopy(const std::string& dir, const Json& run) {
  const auto inputs = run.find("inputs");
  if (inputs == run.end() || !inputs->is_array()) return "";
  for (const auto& input : *inputs) {
    if (input.is_object() && input.value("role", "") == "problem file") {
      return (fs::path(dir) / input.value("copy", "")).string();
    }
  }
  return "";
}

// The arguments of the recorded command with --out NEW, the problem file's copy, and
// --overwrite only when asked for now.
std::vector<std::string> RerunArguments(const std::string& dir, const Json& run,
                                        const std::string& out, bool overwrite) {
  const std::vector<std::string> recorded = RecordedCommandLine(dir, run);
  std::vector<std::string> arguments = {};
  for (std::size_t i = 1; i < recorded.size(); ++i) {
    const std::string& word = recorded[i];
    if (word == "--overwrite") continue;
    arguments.push_back(word);
    if (!TakesValue(word) || i + 1 >= recorded.size()) continue;
    const std::string& value = recorded[++i];
    if (word == "--out") {
      arguments.push_back(out);
    } else if (word == "--problem-file") {
      const std::string copy = ProblemFileCopy(dir, run);
      if (copy.empty()) Refuse(dir, "run.json names a problem file but records no copy of it");
      arguments.push_back(copy);
    } else {
      arguments.push_back(value);
    }
  }
  if (overwrite) arguments.push_back("--overwrite");
  return arguments;
}

std::string Text(const Json& value) {
  return value.is_string() ? value.get<std::string>() : value.is_null() ? "none" : value.dump();
}

// `what` recorded as `recorded`, now `now`: a difference unless equal.
void Compare(const std::string& what, const Json& recorded, const std::string& now,
             std::vector<std::string>* differences) {
  const Json now_json = now.empty() ? Json() : Json(now);
  if (recorded != now_json) {
    differences->push_back(what + ": recorded " + Text(recorded) + ", now " + Text(now_json));
  }
}

Json Field(const Json& run, const char* section, const char* key) {
  const auto s = run.find(section);
  if (s == run.end() || !s->is_object()) return Json();
  const auto v = s->find(key);
  return v == s->end() ? Json() : *v;
}

void CompareBuild(const Json& run, std::vector<std::string>* differences) {
  Compare("version", run.value("version", Json()), CONTACTBENCH_VERSION, differences);
  Compare("commit", run.value("commit", Json()), CONTACTBENCH_COMMIT, differences);
  if (!run.contains("build") || !run.contains("libraries")) {
    differences->push_back(
        "run.json records no build or library versions (written by an older contactbench)");
    return;
  }
  Compare("the binary (build.binary_sha256)", Field(run, "build", "binary_sha256"),
          BinarySha256(RunningBinary()), differences);
  for (const LinkedLibrary& library : LinkedLibraries()) {
    Compare("library " + library.name, Field(run, "libraries", library.name.c_str()),
            library.version, differences);
  }
  Compare("blas", run.value("blas", Json()), BlasDescription(LoadedBlas()), differences);
  const int processes = run.value("processes", 1);
  if (processes != LaunchedProcessCount()) {
    differences->push_back("processes: recorded " + std::to_string(processes) + ", now " +
                           std::to_string(LaunchedProcessCount()) +
                           " (start the rerun as the run was: mpirun -n " +
                           std::to_string(processes) + ")");
  }
}

void CompareInputs(const std::string& dir, const Json& run, std::vector<std::string>* differences) {
  const auto inputs = run.find("inputs");
  if (inputs == run.end() || !inputs->is_array()) return;
  for (const auto& input : *inputs) {
    if (!input.is_object()) continue;
    const std::string copy = input.value("copy", "");
    const fs::path file = fs::path(dir) / copy;
    std::ifstream in(file, std::ios::binary);
    if (!in) {
      differences->push_back("the copy " + copy + " is missing");
      continue;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (Sha256Hex(bytes) != input.value("sha256", "")) {
      differences->push_back("the copy " + copy + " is not the file the run read (its SHA-256 " +
                             "differs from run.json's)");
    }
    if (!input.value("found_by_copy", true)) {
      differences->push_back("the problem file names its " + input.value("role", "input") + " '" +
                             input.value("source", "") +
                             "' outside its directory: the copied problem file reads that, "
                             "not the copy " +
                             copy);
    }
  }
}

}  // namespace

RerunPlan PlanRerun(const std::string& dir, const std::string& out, bool overwrite) {
  const Json run = ReadRunJson(dir);
  std::error_code ec;
  if (fs::equivalent(dir, out, ec)) {
    throw InputError("--out: '" + out + "' is the directory of the run being rerun; give another");
  }
  RerunPlan plan;
  plan.command = RecordedCommandLine(dir, run)[0];
  plan.arguments = RerunArguments(dir, run, out, overwrite);
  CompareBuild(run, &plan.differences);
  CompareInputs(dir, run, &plan.differences);
  return plan;
}

}  // namespace cb::harness
