#include "io/json_node.h"

#include <climits>
#include <cmath>

#include "core/csv.h"
#include "io/input_bounds.h"

namespace cb::io {

std::string Describe(double value) { return FormatDouble(value); }

std::string LineColumn(const std::string& text, std::size_t byte) {
  // nlohmann's byte is the 1-based position of the last character read; past the end it is
  // size + 1 ("unexpected end of input"), which we report at the end of the last line.
  const std::size_t end = std::min(byte == 0 ? 0 : byte - 1, text.size());
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(end - line_start + 1);
}

namespace {

std::string Escape(const std::string& key);

// Follows a SAX parse and knows the JSON pointer of the value being read: where a parse error
// (a number that overflows a double) stopped it.
class PointerTracker final : public nlohmann::json_sax<Json> {
 public:
  std::string pointer() const {
    std::string p;
    for (const Level& level : levels_) p += "/" + level.token;
    return p;
  }

  bool null() override { return Value(); }
  bool boolean(bool) override { return Value(); }
  bool number_integer(number_integer_t) override { return Value(); }
  bool number_unsigned(number_unsigned_t) override { return Value(); }
  bool number_float(number_float_t, const string_t&) override { return Value(); }
  bool string(string_t&) override { return Value(); }
  bool binary(binary_t&) override { return Value(); }
  bool start_object(std::size_t) override { return Open(false); }
  bool key(string_t& key) override {
    levels_.back().token = Escape(key);
    return true;
  }
  bool end_object() override { return Close(); }
  bool start_array(std::size_t) override { return Open(true); }
  bool end_array() override { return Close(); }
  // The value that failed is the next one read.
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    Enter();
    return false;
  }

 private:
  struct Level {
    bool array = false;
    int next = 0;       // an array's index of the next value
    std::string token;  // the reference token of the value being read
  };
  // Before a value in an array: its index is the token.
  void Enter() {
    if (!levels_.empty() && levels_.back().array) {
      levels_.back().token = std::to_string(levels_.back().next++);
    }
  }
  bool Value() {
    Enter();
    return true;
  }
  bool Open(bool array) {
    Enter();
    levels_.push_back({array, 0, ""});
    return true;
  }
  bool Close() {
    levels_.pop_back();
    return true;
  }
  std::vector<Level> levels_;
};

}  // namespace

Json ParseJson(const std::string& text, const std::string& file) {
  CheckJsonDepth(text, file, kJsonMaxDepth);  // before the parser's work grows with it
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    // Keep nlohmann's reason ("syntax error while parsing object - unexpected ...") but state
    // the position in lines and columns, computed from the byte offset.
    std::string reason = e.what();
    const auto column = reason.find("column ");
    const auto colon = reason.find(": ", column == std::string::npos ? 0 : column);
    if (colon != std::string::npos) reason = reason.substr(colon + 2);
    throw InputError(file, LineColumn(text, e.byte), "malformed JSON: " + reason);
  } catch (const Json::exception& e) {
    // A number too large for a double ("number overflow"): nlohmann gives no position; a
    // second pass that follows the document finds the JSON pointer of the number.
    std::string reason = e.what();
    const auto bracket = reason.find("] ");
    if (bracket != std::string::npos) reason = reason.substr(bracket + 2);
    PointerTracker tracker;
    Json::sax_parse(text, &tracker);
    throw InputError(file, tracker.pointer(), "malformed JSON: " + reason);
  }
}

namespace {

// RFC 6901: '~' is written "~0" and '/' "~1" inside a pointer's reference token.
std::string Escape(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

void JsonNode::Fail(const std::string& reason) const { throw InputError(file_, where(), reason); }

std::string JsonNode::TypeName() const {
  if (value_->is_number()) return "a number";
  if (value_->is_string()) return "a string";
  if (value_->is_object()) return "an object";
  if (value_->is_array()) return "an array";
  if (value_->is_boolean()) return "a boolean";
  return "null";
}

void JsonNode::ExpectObject(std::initializer_list<const char*> allowed) const {
  if (!value_->is_object()) Fail("expected an object, got " + TypeName());
  for (const auto& [key, item] : value_->items()) {
    bool known = false;
    for (const char* a : allowed) known = known || key == a;
    if (!known) {
      std::string valid;
      for (const char* a : allowed) valid += (valid.empty() ? "" : ", ") + std::string(a);
      JsonNode(&item, file_, pointer_ + "/" + Escape(key))
          .Fail("unknown field (valid here: " + valid + ")");
    }
  }
}

bool JsonNode::Has(const std::string& key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::Field(const std::string& key) const {
  if (!value_->is_object()) Fail("expected an object, got " + TypeName());
  auto it = value_->find(key);
  if (it == value_->end()) Fail("missing field '" + key + "'");
  return JsonNode(&*it, file_, pointer_ + "/" + Escape(key));
}

std::optional<JsonNode> JsonNode::Optional(const std::string& key) const {
  if (!Has(key)) return std::nullopt;
  return Field(key);
}

std::size_t JsonNode::Size() const {
  if (!value_->is_array()) Fail("expected an array, got " + TypeName());
  return value_->size();
}

JsonNode JsonNode::At(std::size_t i) const {
  if (i >= Size()) Fail("index " + std::to_string(i) + " out of range");
  return JsonNode(&(*value_)[i], file_, pointer_ + "/" + std::to_string(i));
}

std::vector<JsonNode> JsonNode::Items() const {
  std::vector<JsonNode> items;
  const std::size_t n = Size();
  items.reserve(n);
  for (std::size_t i = 0; i < n; ++i) items.push_back(At(i));
  return items;
}

double JsonNode::Number() const {
  if (!value_->is_number()) Fail("expected a number, got " + TypeName());
  const double v = value_->get<double>();
  if (!std::isfinite(v)) Fail("must be finite, got " + Describe(v));
  return v;
}

double JsonNode::Positive() const {
  const double v = Number();
  if (!(v > 0.0)) Fail("must be > 0, got " + Describe(v));
  return v;
}

std::int64_t JsonNode::Integer() const {
  if (value_->is_number_integer()) {
    if (value_->is_number_unsigned() && value_->get<std::uint64_t>() > INT64_MAX) {
      Fail("integer out of range");
    }
    return value_->get<std::int64_t>();
  }
  const double v = Number();
  if (v != std::floor(v) || std::abs(v) > 9.0e15) Fail("must be an integer, got " + Describe(v));
  return static_cast<std::int64_t>(v);
}

int JsonNode::PositiveInt() const {
  const std::int64_t v = Integer();
  if (v < 1 || v > INT_MAX) Fail("must be a positive integer, got " + std::to_string(v));
  return static_cast<int>(v);
}

std::string JsonNode::String() const {
  if (!value_->is_string()) Fail("expected a string, got " + TypeName());
  return value_->get<std::string>();
}

Point JsonNode::Vector(int size) const {
  if (Size() != static_cast<std::size_t>(size)) {
    Fail("expected " + std::to_string(size) + " numbers, got " + std::to_string(Size()));
  }
  Point p(size);
  for (int i = 0; i < size; ++i) p[i] = At(i).Number();
  return p;
}

Vec JsonNode::AnyVector() const {
  const std::size_t n = Size();
  Vec v(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) v[static_cast<Eigen::Index>(i)] = At(i).Number();
  return v;
}

}  // namespace cb::io
