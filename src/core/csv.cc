#include "core/csv.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace cb {

std::string FormatDouble(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (ec != std::errc()) return "nan";
  return std::string(buffer, end);
}

namespace {

// RFC 4180 quoting: only fields with a comma, quote or line break are quoted.
std::string Quote(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) throw std::runtime_error("cannot open '" + path + "' for writing");
  Row header;
  for (const auto& c : columns_) header << c;
  Write(header);
}

CsvWriter::~CsvWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

CsvWriter::Row& CsvWriter::Row::operator<<(std::string_view text) {
  fields_.push_back(Quote(text));
  return *this;
}
CsvWriter::Row& CsvWriter::Row::operator<<(double value) {
  fields_.push_back(FormatDouble(value));
  return *this;
}
CsvWriter::Row& CsvWriter::Row::operator<<(int value) {
  fields_.push_back(std::to_string(value));
  return *this;
}
CsvWriter::Row& CsvWriter::Row::operator<<(long value) {
  fields_.push_back(std::to_string(value));
  return *this;
}
CsvWriter::Row& CsvWriter::Row::operator<<(long long value) {
  fields_.push_back(std::to_string(value));
  return *this;
}
CsvWriter::Row& CsvWriter::Row::operator<<(unsigned long value) {
  fields_.push_back(std::to_string(value));
  return *this;
}
CsvWriter::Row& CsvWriter::Row::operator<<(bool value) {
  fields_.push_back(value ? "true" : "false");
  return *this;
}

void CsvWriter::Write(const Row& row) {
  if (row.fields_.size() != columns_.size()) {
    throw std::logic_error("CSV row for '" + path_ + "' has " + std::to_string(row.fields_.size()) +
                           " fields, header has " + std::to_string(columns_.size()));
  }
  std::string line;
  for (std::size_t i = 0; i < row.fields_.size(); ++i) {
    if (i > 0) line += ',';
    line += row.fields_[i];
  }
  line += '\n';
  // One fwrite of a whole line, then a flush: an interrupted run leaves only whole lines.
  std::fwrite(line.data(), 1, line.size(), file_);
  std::fflush(file_);
}

}  // namespace cb
