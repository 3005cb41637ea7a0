#include "harness/run_json.h"

#include <contactbench_build_info.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/blas_info.h"

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

}  // namespace

std::string RunJsonText(const RunJson& run, int exit_status, const std::string& reason) {
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - run.started_steady).count();
  nlohmann::ordered_json j;
  j["version"] = CONTACTBENCH_VERSION;
  j["commit"] = OrNull(CONTACTBENCH_COMMIT);
  j["blas"] = BlasDescription(LoadedBlas());
  j["command_line"] = run.command_line;
  j["command"] = run.command;
  j["problem"] = OrNull(run.problem);
  j["problem_source"] = run.problem_source;
  j["problem_notes"] = run.problem_notes;
  j["settings"] = run.settings;
  j["formulations"] = run.formulations;
  if (run.command == "compare") {
    j["mode"] = run.mode;
    j["reference"] = OrNull(run.reference);
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
                 {"kinks", run.kinks}};
  j["wall_time_s"] = wall;
  return j.dump(2) + "\n";
}

bool WriteRunJson(const std::string& directory, const RunJson& run, int exit_status,
                  const std::string& reason) {
  const std::string path = directory + "/run.json";
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << RunJsonText(run, exit_status, reason);
    out.close();
    if (!out) {
      std::remove(temporary.c_str());
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  return !ec;
}

}  // namespace cb::harness
