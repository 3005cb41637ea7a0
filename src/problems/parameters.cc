#include "problems/parameters.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/csv.h"

namespace cb {

namespace {

bool ParseDouble(const std::string& text, double* value) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  auto [end, ec] = std::from_chars(first, last, *value);
  return ec == std::errc() && end == last && !text.empty();
}

// An integer written as digits, with an optional minus sign: "1e3" and "8.0" read as numbers but
// are refused as integers, as everywhere else on the command line.
bool IsIntegerText(const std::string& text) {
  const std::size_t first = !text.empty() && text[0] == '-' ? 1 : 0;
  if (first == text.size()) return false;
  for (std::size_t i = first; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
  }
  return true;
}

// Why `v` is refused: which bound it passes, each printed exactly (a bound of 0.4999999 shown
// as 0.5 would contradict the value), and what the parameter is.
std::string OutOfRange(const std::string& text, bool below, double bound, bool exclusive,
                       const std::string& doc) {
  const std::string side =
      below ? (exclusive ? "must be above " : "must be at least ") : "must be at most ";
  return text + " is out of range: it " + side + FormatDouble(bound) +
         (doc.empty() ? "" : " (" + doc + ")");
}

}  // namespace

void Parameters::DeclareReal(const std::string& name, double value, const std::string& doc,
                             double min, double max, bool exclusive_min) {
  Entry e;
  e.name = name;
  e.kind = Kind::kReal;
  e.value = FormatDouble(value);
  e.doc = doc;
  e.min = min;
  e.max = max;
  e.exclusive_min = exclusive_min;
  entries_.push_back(e);
}

void Parameters::DeclareInteger(const std::string& name, int value, const std::string& doc, int min,
                                int max) {
  Entry e;
  e.name = name;
  e.kind = Kind::kInteger;
  e.value = std::to_string(value);
  e.doc = doc;
  e.min = min;
  e.max = max;
  entries_.push_back(e);
}

void Parameters::DeclareChoice(const std::string& name, const std::string& value,
                               const std::string& doc, std::vector<std::string> choices) {
  Entry e;
  e.name = name;
  e.kind = Kind::kChoice;
  e.value = value;
  e.doc = doc;
  e.choices = std::move(choices);
  entries_.push_back(e);
}

const Parameters::Entry& Parameters::Find(const std::string& name) const {
  for (const auto& e : entries_) {
    if (e.name == name) return e;
  }
  std::string known;
  for (const auto& e : entries_) known += (known.empty() ? "" : ", ") + e.name;
  throw std::invalid_argument("unknown parameter '" + name + "' (known: " + known + ")");
}

Parameters::Entry& Parameters::Find(const std::string& name) {
  return const_cast<Entry&>(static_cast<const Parameters*>(this)->Find(name));
}

void Parameters::Set(const std::string& name, const std::string& text) {
  Entry& e = Find(name);
  const std::string where = "parameter '" + name + "'";
  if (e.kind == Kind::kChoice) {
    for (const auto& c : e.choices) {
      if (c == text) {
        e.value = text;
        return;
      }
    }
    std::string valid;
    for (const auto& c : e.choices) valid += (valid.empty() ? "" : ", ") + c;
    throw std::invalid_argument(where + ": '" + text + "' is not one of: " + valid);
  }
  double v = 0.0;
  if (!ParseDouble(text, &v))
    throw std::invalid_argument(where + ": '" + text + "' is not a number");
  if (!std::isfinite(v)) throw std::invalid_argument(where + ": must be finite");
  if (e.kind == Kind::kInteger && (v != std::floor(v) || !IsIntegerText(text))) {
    throw std::invalid_argument(where + ": '" + text + "' is not an integer");
  }
  const bool below = e.exclusive_min ? !(v > e.min) : !(v >= e.min);
  if (below || v > e.max) {
    throw std::invalid_argument(
        where + ": " +
        OutOfRange(text, below, below ? e.min : e.max, below && e.exclusive_min, e.doc));
  }
  e.value = e.kind == Kind::kInteger ? std::to_string(static_cast<long long>(v)) : FormatDouble(v);
}

void Parameters::Apply(const std::map<std::string, std::string>& settings) {
  for (const auto& [k, v] : settings) Set(k, v);
}

double Parameters::Real(const std::string& name) const {
  const Entry& e = Find(name);
  if (e.kind == Kind::kChoice) throw std::logic_error("parameter '" + name + "' is a choice");
  double v = 0.0;
  ParseDouble(e.value, &v);
  return v;
}

int Parameters::Integer(const std::string& name) const {
  const Entry& e = Find(name);
  if (e.kind != Kind::kInteger)
    throw std::logic_error("parameter '" + name + "' is not an integer");
  return std::stoi(e.value);
}

const std::string& Parameters::Choice(const std::string& name) const {
  const Entry& e = Find(name);
  if (e.kind != Kind::kChoice) throw std::logic_error("parameter '" + name + "' is not a choice");
  return e.value;
}

std::string Parameters::Summary() const {
  std::string out;
  for (const auto& e : entries_) out += (out.empty() ? "" : ";") + e.name + "=" + e.value;
  return out;
}

}  // namespace cb
