// Named, documented problem parameters. Every reconstruction choice of docs/problems.md is one of
// these, so that another reading can be tried with `--set KEY=VALUE` and no code change.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace cb {

class Parameters {
 public:
  enum class Kind { kReal, kInteger, kChoice };
  struct Entry {
    std::string name;
    Kind kind = Kind::kReal;
    std::string value;                 // current value as text
    std::string doc;                   // meaning and unit
    std::vector<std::string> choices;  // kChoice only
    double min = 0.0;                  // kReal / kInteger: allowed range [min, max]
    double max = 0.0;
    bool exclusive_min = false;  // kReal: (min, max]
  };

  void DeclareReal(const std::string& name, double value, const std::string& doc, double min,
                   double max, bool exclusive_min = false);
  void DeclareInteger(const std::string& name, int value, const std::string& doc, int min, int max);
  void DeclareChoice(const std::string& name, const std::string& value, const std::string& doc,
                     std::vector<std::string> choices);

  // Sets a declared parameter from text. Throws std::invalid_argument naming the parameter:
  // unknown (listing the known ones), not a number, non-finite, out of range, not a choice.
  void Set(const std::string& name, const std::string& text);
  // Applies every KEY=VALUE of `settings` (Set for each).
  void Apply(const std::map<std::string, std::string>& settings);

  double Real(const std::string& name) const;
  int Integer(const std::string& name) const;
  const std::string& Choice(const std::string& name) const;

  const std::vector<Entry>& entries() const { return entries_; }
  // "name=value;name=value..." in declaration order, for the records.
  std::string Summary() const;

 private:
  const Entry& Find(const std::string& name) const;
  Entry& Find(const std::string& name);
  std::vector<Entry> entries_;
};

}  // namespace cb
