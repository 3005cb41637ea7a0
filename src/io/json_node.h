// Typed, located access to a parsed JSON document: every accessor either returns a value of the
// expected type and range or throws InputError naming the file, the JSON pointer of the value
// (RFC 6901, e.g. /members/3/E) and the reason. Readers use nothing else to look at JSON, so
// every bad input is reported the same way.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "io/input_error.h"

namespace cb::io {

using Json = nlohmann::json;

// Parses `text` (the contents of `file`). Malformed JSON throws InputError with the line and
// column of the offending character (nlohmann reports a byte offset only).
Json ParseJson(const std::string& text, const std::string& file);

// "1-based line:column" of byte offset `byte` (1-based, as nlohmann counts) in `text`.
std::string LineColumn(const std::string& text, std::size_t byte);

class JsonNode {
 public:
  JsonNode(const Json* value, std::string file, std::string pointer)
      : value_(value), file_(std::move(file)), pointer_(std::move(pointer)) {}

  const Json& value() const { return *value_; }
  const std::string& file() const { return file_; }
  // The JSON pointer, "/" for the root.
  std::string where() const { return pointer_.empty() ? "/" : pointer_; }
  [[noreturn]] void Fail(const std::string& reason) const;

  // Objects. ExpectObject checks the type and that every key is one of `allowed` (an unknown
  // field is a misspelling more often than not).
  void ExpectObject(std::initializer_list<const char*> allowed) const;
  bool Has(const std::string& key) const;
  JsonNode Field(const std::string& key) const;  // required: "missing field"
  std::optional<JsonNode> Optional(const std::string& key) const;

  // Arrays.
  std::size_t Size() const;  // checks the type
  JsonNode At(std::size_t i) const;
  std::vector<JsonNode> Items() const;

  // Scalars. Numbers are finite; integers exact (2.0 is accepted, 2.5 is not).
  double Number() const;
  double Positive() const;  // > 0
  std::int64_t Integer() const;
  int PositiveInt() const;  // 1 .. INT_MAX
  std::string String() const;
  // A fixed-length array of numbers.
  Point Vector(int size) const;
  Vec AnyVector() const;

 private:
  std::string TypeName() const;
  const Json* value_;
  std::string file_;
  std::string pointer_;
};

// A number for messages: shortest text that reads back to the same double.
std::string Describe(double value);

}  // namespace cb::io
