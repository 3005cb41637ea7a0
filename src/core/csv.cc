#include "core/csv.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/owned_file.h"

namespace cb {

std::string FormatDouble(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (ec != std::errc()) return "nan";
  return std::string(buffer, end);
}

std::string FormatReal(double value) {
  std::string text = FormatDouble(value);
  // Shortest round-trip text has a '.' or an exponent unless the value is integral; nan and
  // inf read as reals already.
  if (text.find_first_of(".eni") == std::string::npos) text += ".0";
  return text;
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

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns, std::string* memory)
    : path_(path), columns_(std::move(columns)), memory_(memory) {
  if (memory_ != nullptr) {
    memory_->clear();  // as O_TRUNC empties a file
  } else {
    fd_ = OpenOwnedFile(path, FileCreation::kReplace);  // never through a symbolic link
  }
  Row header;
  for (const auto& c : columns_) header << c;
  try {
    Write(header);
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

CsvWriter::~CsvWriter() {
  if (fd_ >= 0) ::close(fd_);
}

CsvWriter::Row& CsvWriter::Row::operator<<(std::string_view text) {
  fields_.push_back(Quote(text));
  return *this;
}
CsvWriter::Row& CsvWriter::Row::operator<<(double value) {
  fields_.push_back(FormatReal(value));
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
  if (memory_ != nullptr) {
    memory_->append(line);
    return;
  }
  // Unbuffered writes of a whole line: an interrupted run leaves only whole lines, and a write
  // that fails part-way is undone here rather than by a later flush of a buffer.
  std::size_t written = 0;
  while (written < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + written, line.size() - written);
    if (n > 0) {
      written += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      const std::string reason = n < 0 ? std::strerror(errno) : "short write";
      // Best effort: a device (/dev/full) cannot be truncated and holds nothing anyway.
      if (::ftruncate(fd_, whole_lines_bytes_) == 0) ::lseek(fd_, whole_lines_bytes_, SEEK_SET);
      throw WriteError(path_, reason);
    }
  }
  whole_lines_bytes_ += static_cast<long long>(line.size());
}

}  // namespace cb
