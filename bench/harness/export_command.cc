#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "harness/cli.h"
#include "harness/cli_commands.h"
#include "harness/commands.h"
#include "harness/fclib_export.h"
#include "io/fclib_file.h"
#include "io/problem_file.h"

namespace cb::harness {

// Writes the problem as a problem file: the suite's JSON, or an FCLIB global problem.
int ExportCommand(const RunArguments& a) {
  const Problem problem = LoadProblem(a);
  const std::filesystem::path out(a.out);
  std::error_code ec;
  if (std::filesystem::is_directory(out, ec)) {
    throw InputError("--out: '" + a.out + "' is a directory; give the problem file's name");
  }
  const std::filesystem::path dir = out.parent_path().empty() ? "." : out.parent_path();
  if (a.export_format == "fclib") {
    if (!io::FclibAvailable()) {
      throw InputError(
          "--format fclib: this build has no HDF5 (install libhdf5-dev, "
          "scripts/packages.txt, and configure again)");
    }
    PrepareOutput(dir.string());
    const std::string what = ExportFclib(a, problem);
    std::fprintf(stderr, "%s -> %s (FCLIB, mu = 0; %s)\n", problem.name.c_str(), a.out.c_str(),
                 what.c_str());
    return kExitOk;
  }
  if (a.export_step) throw UsageError("--step: only with --format fclib");
  std::string text;
  try {
    text = io::ProblemToJson(problem);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  PrepareOutput(dir.string());
  std::ofstream file(out, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw InputError("--out: cannot write '" + a.out + "'");
  std::fprintf(stderr, "%s -> %s\n", problem.name.c_str(), a.out.c_str());
  return kExitOk;
}

}  // namespace cb::harness
