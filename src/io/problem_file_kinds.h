// One reader per kind of problem file ("kind": "truss", "plane-stress-q4", "solid-hex8",
// "lcp"), each in its own file; ParseProblemFile (problem_file_reader.cc) picks one.
#pragma once

#include <map>
#include <string>

#include "io/json_node.h"
#include "problems/problem.h"

namespace cb::io::reading {

using Settings = std::map<std::string, std::string>;

Problem ReadTruss(const JsonNode& root, const std::string& file, const Settings& settings);
Problem ReadPlaneStress(const JsonNode& root, const std::string& file, const std::string& directory,
                        const Settings& settings);
Problem ReadSolidHex8(const JsonNode& root, const std::string& file, const std::string& directory,
                      const Settings& settings);
Problem ReadLcp(const JsonNode& root, const std::string& file, const Settings& settings);

}  // namespace cb::io::reading
