// Tests of refusals assert what a message means, not how it is worded (docs/contributing.md):
// where the input is bad (the file, the JSON pointer or mesh line, the option) and what the
// message names there (the field, the id, the bad value), each as it appears in the input, in
// any order. Rewording a message leaves these tests passing; losing the pointer or the value
// a user needs to find the mistake fails them.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <charconv>
#include <string>
#include <utility>
#include <vector>

namespace cb::testing_support {

// Where a refusal points and what it names.
struct Refusal {
  std::string where;               // "/members/1/E", "line 2"; "" when the test leaves it open
  std::vector<std::string> names;  // each must appear in the reason
};

// A refusal at `where` naming `names`.
inline Refusal At(std::string where, std::vector<std::string> names = {}) {
  return {std::move(where), std::move(names)};
}

// Success when `message` names every one of `names`.
inline ::testing::AssertionResult Names(const std::string& message,
                                        const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    if (message.find(name) == std::string::npos) {
      return ::testing::AssertionFailure() << "\"" << message << "\" does not name " << name;
    }
  }
  return ::testing::AssertionSuccess();
}

// The numbers written in `message`, in order: each run of digits (with a sign, a point or an
// exponent) that does not continue a word, as from_chars reads it ("0.4999999", "-1", "1e-12";
// "steps 2-6" gives 2 and 6; "P1" and "x86_64" give none).
inline std::vector<double> NumbersIn(const std::string& message) {
  std::vector<double> numbers;
  auto in_word = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.';
  };
  const char* const end = message.data() + message.size();
  std::size_t i = 0;
  while (i < message.size()) {
    const char c = message[i];
    const bool digit_next =
        i + 1 < message.size() && std::isdigit(static_cast<unsigned char>(message[i + 1])) != 0;
    const bool starts =
        std::isdigit(static_cast<unsigned char>(c)) != 0 || ((c == '-' || c == '.') && digit_next);
    if (!starts || (i > 0 && in_word(message[i - 1]))) {
      ++i;
      continue;
    }
    double value = 0.0;
    const auto [next, error] = std::from_chars(message.data() + i, end, value);
    if (error != std::errc()) {
      ++i;
      continue;
    }
    numbers.push_back(value);
    i = static_cast<std::size_t>(next - message.data());
  }
  return numbers;
}

// Success when `message` writes the number `value` (exactly, as NumbersIn reads it).
inline ::testing::AssertionResult NamesNumber(const std::string& message, double value) {
  for (const double number : NumbersIn(message)) {
    if (number == value) return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "\"" << message << "\" does not give " << value;
}

// Success when `message` is an input error of `file` ("FILE: WHERE: reason", io::InputError)
// at `expected.where` whose reason names every one of `expected.names`.
inline ::testing::AssertionResult RefusedAt(const std::string& message, const std::string& file,
                                            const Refusal& expected) {
  const std::string head = file + ": ";
  if (message.rfind(head, 0) != 0) {
    return ::testing::AssertionFailure() << "\"" << message << "\" does not name " << file;
  }
  std::string reason = message.substr(head.size());
  if (!expected.where.empty()) {
    const std::string at = expected.where + ": ";
    if (reason.rfind(at, 0) != 0) {
      return ::testing::AssertionFailure()
             << "\"" << message << "\" does not point at " << expected.where;
    }
    reason = reason.substr(at.size());
  }
  return Names(reason, expected.names);
}

// The refusal in a command's output: what follows "contactbench: " on the first line that starts
// so ("" when there is none).
inline std::string RefusalLine(const std::string& output) {
  const std::string head = "contactbench: ";
  std::size_t at = output.rfind(head, 0) == 0 ? 0 : output.find("\n" + head);
  if (at == std::string::npos) return "";
  if (output[at] == '\n') ++at;
  const std::size_t end = output.find('\n', at);
  return output.substr(at + head.size(), end == std::string::npos ? end : end - at - head.size());
}

// Success when `output` holds a refusal of the command line ("contactbench: WHERE: reason" or
// "contactbench: WHERE reason") at `expected.where`, the option or the command as typed
// ("--steps", "run"; "" leaves it open), whose reason names every one of `expected.names`.
inline ::testing::AssertionResult RefusedOption(const std::string& output,
                                                const Refusal& expected) {
  std::string reason = RefusalLine(output);
  if (reason.empty()) return ::testing::AssertionFailure() << "no refusal in \"" << output << "\"";
  if (!expected.where.empty()) {
    const bool at = reason.rfind(expected.where, 0) == 0 &&
                    (reason.size() == expected.where.size() ||
                     reason[expected.where.size()] == ':' || reason[expected.where.size()] == ' ');
    if (!at) {
      return ::testing::AssertionFailure()
             << "\"" << reason << "\" does not point at " << expected.where;
    }
    reason = reason.substr(expected.where.size());
  }
  return Names(reason, expected.names);
}

}  // namespace cb::testing_support
