// The value parsers of contactbench's options: numbers, integers, lists, choices and
// KEY=VALUE settings, each refusing a bad value with a UsageError naming the option. Internal
// to the option table (option_table.cc), the parser (options.cc) and the usage text.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "harness/options.h"

namespace cb::harness::option_values {

bool Contains(const std::vector<std::string>& items, const std::string& item);

// Whether `command` takes `option`.
inline bool Takes(const Option& option, Command command) {
  return (option.commands & command) != 0;
}

[[noreturn]] void Refuse(const Option& option, const std::string& why);

double ParseNumber(const Option& option, const std::string& text);
int ParseInteger(const Option& option, const std::string& text);
double PositiveNumber(const Option& option, const std::string& text);
// The verdict's tolerance: positive and at most kMaxVerdictTolerance.
double VerdictTolerance(const Option& option, const std::string& text);
int NonNegativeInteger(const Option& option, const std::string& text);

// The comma-separated items of `text`, each without the blanks around it ("a, b" as "a,b": a
// list typed with the spaces of prose); empty items are dropped.
std::vector<std::string> SplitList(const std::string& text);
// A comma-separated list with no empty item ("a,,b", ",", "" are refused: an empty list would
// silently mean the default).
std::vector<std::string> NonEmptyList(const Option& option, const std::string& text);
// `value` if it is one of the option's choices.
const std::string& Choice(const Option& option, const std::string& value);
// KEY=VALUE into (key, value).
std::pair<std::string, std::string> KeyValue(const Option& option, const std::string& kv);
// [FORMULATION:]KEY=VALUE: a setting of the formulation named, or of every formulation.
void FormulationOption(const Option& option, const std::string& text, bool prefix_required,
                       RunArguments* a);

StartKind ParseStart(const std::string& text);
// The choices of --starts, --start, --mode and --bifurcations.
std::vector<std::string> Starts();
std::vector<std::string> RunStarts();
std::vector<std::string> Modes();
std::vector<std::string> BifurcationModes();

}  // namespace cb::harness::option_values
