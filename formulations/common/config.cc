#include "formulations/common/config.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace cb {

OptionReader::OptionReader(std::string formulation,
                           const std::map<std::string, std::string>& options)
    : formulation_(std::move(formulation)), options_(options) {}

const std::string* OptionReader::Find(const std::string& key) {
  known_.insert(key);
  auto it = options_.find(key);
  return it == options_.end() ? nullptr : &it->second;
}

double OptionReader::GetReal(const std::string& key, double fallback) {
  const std::string* text = Find(key);
  if (text == nullptr) return fallback;
  double v = 0.0;
  auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), v);
  if (ec != std::errc() || end != text->data() + text->size() || !std::isfinite(v)) {
    throw std::invalid_argument(formulation_ + " option '" + key + "': '" + *text +
                                "' is not a finite number");
  }
  return v;
}

std::string OptionReader::GetText(const std::string& key, const std::string& fallback) {
  const std::string* text = Find(key);
  return text == nullptr ? fallback : *text;
}

int OptionReader::GetInteger(const std::string& key, int fallback) {
  const std::string* text = Find(key);
  if (text == nullptr) return fallback;
  int v = 0;
  auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), v);
  if (ec != std::errc() || end != text->data() + text->size()) {
    throw std::invalid_argument(formulation_ + " option '" + key + "': '" + *text +
                                "' is not an integer");
  }
  return v;
}

std::string OptionReader::GetChoice(const std::string& key, const std::string& fallback,
                                    const std::vector<std::string>& choices) {
  const std::string* text = Find(key);
  if (text == nullptr) return fallback;
  for (const auto& c : choices) {
    if (c == *text) return c;
  }
  std::string valid;
  for (const auto& c : choices) valid += (valid.empty() ? "" : ", ") + c;
  throw std::invalid_argument(formulation_ + " option '" + key + "': '" + *text +
                              "' is not one of: " + valid);
}

bool OptionReader::GetBool(const std::string& key, bool fallback) {
  const std::string* text = Find(key);
  if (text == nullptr) return fallback;
  if (*text == "true" || *text == "1") return true;
  if (*text == "false" || *text == "0") return false;
  throw std::invalid_argument(formulation_ + " option '" + key + "': '" + *text +
                              "' is not true or false");
}

void OptionReader::Finish() const {
  for (const auto& [key, value] : options_) {
    if (known_.count(key) == 0) {
      std::string valid;
      for (const auto& k : known_) valid += (valid.empty() ? "" : ", ") + k;
      throw UnknownOptionError("unknown " + formulation_ + " option '" + key +
                                   "' (known: " + (valid.empty() ? "none" : valid) + ")",
                               key, std::vector<std::string>(known_.begin(), known_.end()));
    }
  }
}

}  // namespace cb
