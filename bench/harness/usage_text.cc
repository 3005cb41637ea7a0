// The usage text of contactbench and each command's --help, laid out from the option table:
// what is parsed and what is documented cannot drift apart.
#include <string>
#include <vector>

#include "harness/option_values.h"
#include "harness/options.h"

namespace cb::harness {

namespace {

using option_values::Takes;

constexpr std::size_t kWidth = 96;

// `words` filled into lines of at most kWidth columns; the first line continues a text of
// `used` columns, the others start with `indent` spaces. A word longer than a line stays whole.
std::string Fill(const std::vector<std::string>& words, std::size_t used, std::size_t indent) {
  std::string out;
  std::size_t column = used;
  bool line_start = true;
  for (const auto& word : words) {
    if (!line_start && column + 1 + word.size() > kWidth) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
      line_start = true;
    }
    if (!line_start) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    line_start = false;
  }
  return out;
}

std::vector<std::string> Words(const std::string& text) {
  std::vector<std::string> words;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t space = text.find(' ', start);
    const std::size_t end = space == std::string::npos ? text.size() : space;
    if (end > start) words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return words;
}

// The usage items of a command: the problem's options as one alternative, the required
// options, then the optional ones in brackets.
std::vector<std::string> UsageItems(Command command) {
  std::vector<std::string> problem, required, optional;
  for (const Option& o : Options()) {
    if (!Takes(o, command)) continue;
    const std::string item = NameAndValue(o) + (o.repeatable ? " ..." : "");
    if (o.need == Need::kProblem) problem.push_back(item);
    if (o.need == Need::kRequired) required.push_back(item);
    if (o.need == Need::kOptional) optional.push_back("[" + item + "]");
  }
  std::vector<std::string> items;
  for (const CommandInfo& c : Commands()) {
    if (c.command == command && c.operand != nullptr) items.emplace_back(c.operand);
  }
  if (problem.size() == 1) items.push_back(problem.front());
  if (problem.size() > 1)
    items.push_back(std::string("(").append(Join(problem, " | ")).append(")"));
  items.insert(items.end(), required.begin(), required.end());
  items.insert(items.end(), optional.begin(), optional.end());
  return items;
}

// `prefix` contactbench COMMAND ITEMS..., continued lines aligned under the first item.
std::string UsageLine(const CommandInfo& command, const std::string& prefix) {
  const std::string head = prefix + "contactbench " + command.name;
  return head + " " + Fill(UsageItems(command.command), head.size(), head.size() + 1) + "\n";
}

constexpr const char* kExitStatus =
    "Exit status: 0 every step verified; 2 bad arguments (or a bad problem file, a problem too "
    "large for the memory, or an output that cannot be written); 3 stopped on a failure (a "
    "step, a stagnating path, a write, out of memory; records kept); 4 interrupted by SIGINT or "
    "SIGTERM (records kept).";

}  // namespace

std::string NameAndValue(const Option& o) {
  return *o.placeholder == '\0' ? std::string(o.name) : std::string(o.name) + " " + o.placeholder;
}

std::string Join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : separator) + s;
  return out;
}

std::string Synopsis(const CommandInfo& command) { return UsageLine(command, "usage: "); }

std::string UsageText() {
  std::string text = "usage:\n";
  for (const CommandInfo& c : Commands()) text += UsageLine(c, "  ");
  text += "  contactbench help\n  contactbench --version\n\n";
  text += Fill(Words("`contactbench COMMAND --help` says what a command does and what each of "
                     "its options means."),
               0, 0) +
          "\n";
  return text + Fill(Words(kExitStatus), 0, 0) + "\n";
}

std::string CommandHelp(const CommandInfo& command) {
  std::string text = Synopsis(command) + "\n";
  text += Fill(Words(std::string(command.summary)), 0, 0) + "\n\n";
  constexpr std::size_t kHelpColumn = 30;
  if (command.operand != nullptr) {
    std::string line = std::string("  ") + command.operand;
    line.resize(kHelpColumn, ' ');
    text += line + Fill(Words(command.operand_help), kHelpColumn, kHelpColumn) + "\n\n";
  }
  text += "options:\n";
  for (const Option& o : Options()) {
    if (!Takes(o, command.command)) continue;
    std::string line = "  " + NameAndValue(o);
    line += line.size() + 2 <= kHelpColumn ? std::string(kHelpColumn - line.size(), ' ')
                                           : "\n" + std::string(kHelpColumn, ' ');
    std::string help = o.help;
    if (o.choices != nullptr) help += "; one of: " + Join(o.choices());
    text += line + Fill(Words(help), kHelpColumn, kHelpColumn) + "\n";
  }
  // The exit statuses are those of the commands that load a problem.
  if ((command.command & (kRun | kCompare | kExport)) == 0) return text;
  return text + "\n" + Fill(Words(kExitStatus), 0, 0) + "\n";
}

}  // namespace cb::harness
