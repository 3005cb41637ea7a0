#include <cstdio>
#include <string>

#include "harness/cli_commands.h"
#include "harness/plugins.h"
#include "harness/rerun.h"
#include "harness/run_json.h"

namespace cb::harness {

// `contactbench rerun DIR --out NEW`: the recorded command again (rerun.h), refused when it
// would not be the same run unless --force.
int RerunCommand(const RunArguments& a) {
  const RerunPlan plan = PlanRerun(a.operand, a.out, a.overwrite);
  if (!plan.differences.empty()) {
    const std::string listed = "\n  " + Join(plan.differences, "\n  ");
    if (!a.force) {
      throw InputError("rerun: refused, '" + a.operand + "' was made otherwise:" + listed +
                       "\n(--force reruns it anyway)");
    }
    std::fprintf(stderr, "rerun: --force: rerunning although%s\n", listed.c_str());
  }
  const CommandInfo* command = FindCommand(plan.command);
  for (const auto& plugin : PluginPaths(plan.arguments)) LoadPlugin(plugin);  // as Main does
  const RunArguments arguments = ParseArguments(command->command, plan.arguments);
  RunJson record;
  record.command_line = {RunningBinary(), plan.command};
  record.command_line.insert(record.command_line.end(), plan.arguments.begin(),
                             plan.arguments.end());
  record.command = plan.command;
  record.rerun_of = a.operand;
  return Execute(command->command, arguments, &record);
}

}  // namespace cb::harness
