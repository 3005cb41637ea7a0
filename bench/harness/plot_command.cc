#include "harness/plot_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "harness/cli.h"

namespace cb::harness {

std::vector<std::string> PlotScriptCandidates() {
  std::vector<std::string> candidates;
  std::error_code ec;
  const std::filesystem::path binary = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    candidates.push_back(
        (binary.parent_path().parent_path() / "share" / "contactbench" / "plot_run.py").string());
  }
  candidates.push_back(std::string(CONTACTBENCH_SOURCE_DIR) + "/results/plot_run.py");
  return candidates;
}

int RunPlotScript(const RunArguments& a) {
  std::string script;
  for (const std::string& candidate : PlotScriptCandidates()) {
    if (std::filesystem::is_regular_file(candidate)) {
      script = candidate;
      break;
    }
  }
  if (script.empty()) {
    throw InputError("plot: cannot find plot_run.py (looked for " + Join(PlotScriptCandidates()) +
                     ")");
  }
  std::vector<std::string> args = {"python3", script, a.operand};
  if (a.plot_step) args.insert(args.end(), {"--step", std::to_string(*a.plot_step)});
  if (!a.figures.empty()) args.insert(args.end(), {"--figures", a.figures});
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("plot: cannot start python3");
  if (pid == 0) {
    execv("/usr/bin/python3", argv.data());  // Debian's, with python3-matplotlib
    execvp("python3", argv.data());
    _exit(127);
  }
  int raw = 0;
  while (waitpid(pid, &raw, 0) < 0) {
  }
  if (!WIFEXITED(raw)) return kExitFailure;
  const int status = WEXITSTATUS(raw);
  return status == 0 ? kExitOk : status == 2 ? kExitBadArguments : kExitFailure;
}

}  // namespace cb::harness
