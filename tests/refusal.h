// Tests of refusals assert what a message means, not how it is worded (docs/contributing.md):
// where the input is bad (the file, the JSON pointer or mesh line, the option) and what the
// message names there (the field, the id, the bad value), each as it appears in the input, in
// any order. Rewording a message leaves these tests passing; losing the pointer or the value
// a user needs to find the mistake fails them.
#pragma once

#include <gtest/gtest.h>

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

}  // namespace cb::testing_support
