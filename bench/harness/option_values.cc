#include "harness/option_values.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "formulations/registry.h"
#include "harness/suggest.h"

namespace cb::harness::option_values {

bool Contains(const std::vector<std::string>& items, const std::string& item) {
  return std::find(items.begin(), items.end(), item) != items.end();
}

[[noreturn]] void Refuse(const Option& option, const std::string& why) {
  throw UsageError(std::string(option.name) + ": " + why);
}

namespace {

// Decimal notation only ("16", "-2.5", "1e-3"): strtod would also read hexadecimal ("0x10"),
// "inf" and "nan", which no option means.
bool IsDecimalNumber(const std::string& text) {
  std::size_t i = 0;
  auto digits = [&] {
    const std::size_t start = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
    return i > start;
  };
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  bool mantissa = digits();
  if (i < text.size() && text[i] == '.') {
    ++i;
    mantissa = digits() || mantissa;
  }
  if (!mantissa) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == text.size();
}

}  // namespace

double ParseNumber(const Option& option, const std::string& text) {
  const std::string lower = [&] {
    std::string l = text;
    for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return l;
  }();
  if (lower.find("inf") != std::string::npos) Refuse(option, "must be finite, got '" + text + "'");
  if (!IsDecimalNumber(text)) Refuse(option, "'" + text + "' is not a decimal number");
  errno = 0;
  const double v = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(v)) Refuse(option, "must be finite, got '" + text + "'");
  // A value below the smallest normal double is rounded to a subnormal or to 0 (ERANGE): say
  // so, rather than use a number that is not the one written.
  if (v != 0.0 && !std::isnormal(v)) {
    Refuse(option, "'" + text + "' is too small: below the smallest normal double (2.2e-308)");
  }
  if (errno == ERANGE && v == 0.0) {
    Refuse(option, "'" + text + "' is too small: it underflows to 0");
  }
  return v;
}

int ParseInteger(const Option& option, const std::string& text) {
  const bool decimal_integer =
      !text.empty() &&
      std::all_of(text.begin() + (text[0] == '-' || text[0] == '+' ? 1 : 0), text.end(),
                  [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }) &&
      text != "-" && text != "+";
  if (!decimal_integer) Refuse(option, "'" + text + "' is not a decimal integer");
  const double v = ParseNumber(option, text);
  // Range first: converting a double outside int's range is undefined.
  if (v < INT_MIN || v > INT_MAX) Refuse(option, "'" + text + "' is not an integer in range");
  return static_cast<int>(v);
}

double PositiveNumber(const Option& option, const std::string& text) {
  const double v = ParseNumber(option, text);
  if (!(v > 0.0)) Refuse(option, "must be positive");
  return v;
}

double VerdictTolerance(const Option& option, const std::string& text) {
  const double v = PositiveNumber(option, text);
  if (v > kMaxVerdictTolerance) {
    std::ostringstream bound;
    bound << kMaxVerdictTolerance;
    Refuse(option, "must be at most " + bound.str() + " (the verdict's range), got '" + text + "'");
  }
  return v;
}

int NonNegativeInteger(const Option& option, const std::string& text) {
  const int v = ParseInteger(option, text);
  if (v < 0) Refuse(option, "must be >= 0");
  return v;
}

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    std::size_t end = comma == std::string::npos ? text.size() : comma;
    while (start < end && (text[start] == ' ' || text[start] == '\t')) ++start;
    while (end > start && (text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
    if (end > start) items.push_back(text.substr(start, end - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

std::vector<std::string> NonEmptyList(const Option& option, const std::string& text) {
  std::vector<std::string> items = SplitList(text);
  if (items.empty()) Refuse(option, "the list '" + text + "' names nothing");
  if (std::count(text.begin(), text.end(), ',') + 1 != static_cast<long>(items.size())) {
    Refuse(option, "the list '" + text + "' has an empty name");
  }
  return items;
}

const std::string& Choice(const Option& option, const std::string& value) {
  const std::vector<std::string> valid = option.choices();
  if (!Contains(valid, value))
    Refuse(option,
           "unknown '" + value + "'" + DidYouMean(value, valid) + " (valid: " + Join(valid) + ")");
  return value;
}

std::pair<std::string, std::string> KeyValue(const Option& option, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0) Refuse(option, "expected KEY=VALUE, got '" + kv + "'");
  return {kv.substr(0, eq), kv.substr(eq + 1)};
}

void FormulationOption(const Option& option, const std::string& text, bool prefix_required,
                       RunArguments* a) {
  const auto colon = text.find(':');
  const auto eq = text.find('=');
  const bool prefixed = colon != std::string::npos && colon < eq;
  if (prefix_required && !prefixed) {
    Refuse(option, "expected FORMULATION:KEY=VALUE, got '" + text + "'");
  }
  const std::string owner = prefixed ? text.substr(0, colon) : "";
  if (prefixed && !Contains(FormulationNames(), owner)) {
    Refuse(option, "unknown formulation '" + owner + "'" + DidYouMean(owner, FormulationNames()) +
                       " (valid: " + Join(FormulationNames()) + ")");
  }
  const auto [key, value] = KeyValue(option, prefixed ? text.substr(colon + 1) : text);
  a->options[owner][key] = value;
}

StartKind ParseStart(const std::string& text) {
  return text == "cold" ? StartKind::kCold : StartKind::kWarm;
}

std::vector<std::string> Starts() { return {"warm", "cold"}; }
std::vector<std::string> RunStarts() { return {"warm", "cold", "near"}; }
std::vector<std::string> Modes() { return {"replay", "free"}; }
std::vector<std::string> BifurcationModes() { return {"off", "detect", "switch"}; }

}  // namespace cb::harness::option_values
