// The parser of contactbench's command lines: each argument looked up in the option table
// (option_table.cc) and parsed by its entry, then the checks that need all of them.
#include "harness/options.h"

#include <set>

#include "formulations/registry.h"
#include "harness/option_values.h"
#include "harness/suggest.h"

namespace cb::harness {

namespace {

using option_values::Contains;
using option_values::Takes;

const Option* FindOption(const std::string& name, Command command) {
  for (const Option& o : Options()) {
    if (o.name == name && Takes(o, command)) return &o;
  }
  return nullptr;
}

std::vector<std::string> OptionNames(Command command) {
  std::vector<std::string> names;
  for (const Option& o : Options()) {
    if (Takes(o, command) && !Contains(names, o.name)) names.push_back(o.name);
  }
  return names;
}

std::string ValidList(const Option& o) {
  return o.choices == nullptr ? "" : " (valid: " + Join(o.choices()) + ")";
}

// The problem is given by exactly one of its options; the required options are given.
void CheckNeeds(Command command, const std::set<std::string>& given, bool out_optional) {
  std::vector<std::string> problem_given, problem_forms;
  const Option* first_problem_option = nullptr;
  for (const Option& o : Options()) {
    if (!Takes(o, command) || o.need != Need::kProblem) continue;
    if (first_problem_option == nullptr) first_problem_option = &o;
    if (given.count(o.name)) problem_given.push_back(o.name);
    problem_forms.push_back(NameAndValue(o));
  }
  if (problem_given.size() > 1) {
    throw UsageError("give either " + Join(problem_given, " or ") + ", not both");
  }
  if (first_problem_option != nullptr && problem_given.empty()) {
    throw UsageError(Join(problem_forms, " or ") + " is required" +
                     ValidList(*first_problem_option));
  }
  for (const Option& o : Options()) {
    if (out_optional && std::string_view(o.name) == "--out") continue;
    if (Takes(o, command) && o.need == Need::kRequired && !given.count(o.name)) {
      throw UsageError(NameAndValue(o) + " is required" + ValidList(o));
    }
  }
}

// A problem set's solves are fixed-load, cold and from the files' guesses: the options of
// paths and of their starts would be ignored, so they are refused.
void RefuseForProblemSets(const std::set<std::string>& given) {
  for (const char* name : {"--starts", "--mode", "--reference", "--steps", "--arc-length"}) {
    if (given.count(name)) {
      throw UsageError(std::string(name) +
                       ": not with --problem-dir (its solves are fixed-load, cold and from "
                       "each file's guesses)");
    }
  }
}

void ApplyCompareDefaults(RunArguments* a) {
  if (a->formulations.empty()) {
    for (const auto& info : FormulationRegistry()) {
      if (info.available) a->formulations.push_back(info.name);
    }
  }
  if (a->starts.empty()) a->starts = {StartKind::kWarm};
}

}  // namespace

RunArguments ParseArguments(Command command, const std::vector<std::string>& args,
                            bool out_optional) {
  const CommandInfo* info = nullptr;
  for (const CommandInfo& c : Commands()) {
    if (c.command == command) info = &c;
  }
  if (info == nullptr) throw std::logic_error("ParseArguments: a command without CommandInfo");
  const char* command_name = info->name;
  RunArguments a;
  std::set<std::string> given;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& name = args[i];
    if (info->operand != nullptr && (name.empty() || name[0] != '-')) {
      if (!a.operand.empty()) throw UsageError(std::string(info->operand) + " is given twice");
      a.operand = name;
      continue;
    }
    const Option* o = FindOption(name, command);
    if (o == nullptr) {
      throw UsageError(std::string(command_name) + ": unknown option '" + name + "'" +
                       DidYouMean(name, OptionNames(command)) +
                       " (valid: " + Join(OptionNames(command)) + ")");
    }
    const bool repeated = !given.insert(name).second;
    if (repeated && !o->repeatable) throw UsageError(name + " is given twice");
    const bool flag = *o->placeholder == '\0';
    if (!flag && i + 1 >= args.size()) throw UsageError(name + " needs a value");
    o->parse(*o, flag ? std::string() : args[++i], &a);
    if (a.help) return a;
  }
  CheckNeeds(command, given, out_optional);
  if (info->operand != nullptr && a.operand.empty()) {
    throw UsageError(std::string(info->operand) + " is required");
  }
  if (command == kCompare) ApplyCompareDefaults(&a);
  if (given.count("--problem-dir")) RefuseForProblemSets(given);
  return a;
}

}  // namespace cb::harness
