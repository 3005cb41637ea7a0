#include "harness/run_json.h"

#include <contactbench_build_info.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "core/blas_info.h"
#include "core/csv.h"
#include "core/owned_file.h"
#include "formulations/registry.h"
#include "harness/sha256.h"
#include "parallel/processes.h"

namespace cb::harness {

namespace {

// ISO 8601 in UTC, to the second.
std::string Iso8601(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

nlohmann::ordered_json OrNull(const std::string& text) {
  return text.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(text);
}

nlohmann::ordered_json Load(const std::array<double, 3>& load) {
  if (load[0] < 0.0) return nlohmann::ordered_json();  // unknown
  return {{"1min", load[0]}, {"5min", load[1]}, {"15min", load[2]}};
}

}  // namespace

std::string RunningBinary() {
  std::error_code ec;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? "" : path.string();
}

std::string BinarySha256(const std::string& binary) {
  static std::string cached_binary, cached_hash;  // a build does not change under a process
  if (binary.empty()) return "";
  if (binary == cached_binary) return cached_hash;
  std::ifstream in(binary, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  cached_binary = binary;
  cached_hash = in.bad() || bytes.empty() ? "" : Sha256Hex(bytes);
  return cached_hash;
}

nlohmann::ordered_json BuildJson() {
  const std::string binary = RunningBinary();
  return {{"compiler", CONTACTBENCH_COMPILER},
          {"build_type", CONTACTBENCH_BUILD_TYPE},
          {"cxx_flags", CONTACTBENCH_CXX_FLAGS},
          {"binary", OrNull(binary)},
          {"binary_sha256", OrNull(BinarySha256(binary))}};
}

nlohmann::ordered_json LibrariesJson() {
  nlohmann::ordered_json libraries = nlohmann::ordered_json::object();
  for (const LinkedLibrary& library : LinkedLibraries()) {
    libraries[library.name] = OrNull(library.version);
  }
  return libraries;
}

std::string RunJsonText(const RunJson& run, int exit_status, const std::string& reason) {
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - run.started_steady).count();
  nlohmann::ordered_json j;
  j["version"] = CONTACTBENCH_VERSION;
  j["commit"] = OrNull(CONTACTBENCH_COMMIT);
  j["build"] = BuildJson();
  j["libraries"] = LibrariesJson();
  j["blas"] = BlasDescription(LoadedBlas());
  const Machine machine = ThisMachine();
  j["machine"] = {{"hostname", machine.hostname},
                  {"cpu_model", OrNull(machine.cpu_model)},
                  {"logical_cpus", machine.logical_cpus},
                  {"available_cpus", machine.available_cpus}};
  j["load_average"] = {{"start", Load(run.load_at_start)}, {"end", Load(LoadAverage())}};
  j["processes"] = ProcessCount();
  j["command_line"] = run.command_line;
  j["command"] = run.command;
  j["problem"] = OrNull(run.problem);
  j["problem_source"] = run.problem_source;
  j["inputs"] = nlohmann::ordered_json::array();
  for (const CopiedInput& input : run.inputs) {
    j["inputs"].push_back({{"role", input.role},
                           {"source", input.source},
                           {"copy", input.copy},
                           {"sha256", input.sha256},
                           {"found_by_copy", input.found_by_copy}});
  }
  if (!run.rerun_of.empty()) j["rerun_of"] = run.rerun_of;
  j["problem_notes"] = run.problem_notes;
  j["control"] = OrNull(run.control);
  j["settings"] = run.settings;
  j["formulations"] = run.formulations;
  if (run.command == "compare") {
    j["mode"] = run.mode;
    j["reference"] = OrNull(run.reference);
    j["repeat"] = run.repeat;
  }
  j["starts"] = run.starts;
  j["tolerance"] = run.tolerance;
  j["time_limit_s"] =
      run.time_limit_s > 0.0 ? nlohmann::ordered_json(run.time_limit_s) : nlohmann::ordered_json();
  j["started_at"] = Iso8601(run.started);
  j["exit_status"] = exit_status;
  j["reason"] = reason;
  j["counts"] = {{"runs", run.runs},
                 {"attempts", run.attempts},
                 {"accepted_steps", run.accepted_steps},
                 {"kinks", run.kinks},
                 {"repeat_disagreements", run.repeat_disagreements}};
  j["wall_time_s"] = wall;
  return j.dump(2) + "\n";
}

bool WriteRunJson(const std::string& directory, const RunJson& run, int exit_status,
                  const std::string& reason) {
  const std::string path = directory + "/run.json";
  const std::string temporary = path + ".tmp";
  try {
    // A fresh file, never through a symbolic link; rename replaces a link named run.json
    // rather than writing through it.
    WriteOwnedFile(temporary, RunJsonText(run, exit_status, reason), FileCreation::kReplace);
  } catch (const WriteError&) {
    return false;
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  return !ec;
}

}  // namespace cb::harness
