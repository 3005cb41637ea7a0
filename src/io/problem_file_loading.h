// The parts of a problem file every kind shares: how it is loaded ("analysis", "load",
// "arc_length", "steps"), the run parameters `--set` may change, the version, and optional
// strings. Internal to the problem-file reader (problem_file_reader.cc).
#pragma once

#include <map>
#include <string>

#include "io/json_node.h"
#include "problems/problem.h"

namespace cb::io::reading {

// How the problem is loaded, as the file states it.
struct Loading {
  LoadingKind kind = LoadingKind::kFixedLoad;
  double load = 1.0;
  double arc_length = 0.1;
  int steps = 1;
};

Loading ReadLoading(const JsonNode& root);

// The run parameters `--set` may change, with the file's values as defaults.
Parameters RunParameters(double length_scale, double force_scale, const Loading& loading,
                         bool complementarity);

// Applies `--set`; a bad setting is refused as an input error of `file`.
void ApplySettings(const std::string& file, const std::map<std::string, std::string>& settings,
                   Parameters* p);

void ReadVersion(const JsonNode& root);

std::string OptionalString(const JsonNode& root, const char* key, const std::string& fallback);

}  // namespace cb::io::reading
