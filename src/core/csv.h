// Long-format CSV records, written and flushed row by row so that a run that stops early
// keeps every complete line (docs/architecture.md, house rule 7).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace cb {

// Formats a double in the shortest form that reads back to the same value ("nan", "inf").
std::string FormatDouble(double value);

class CsvWriter {
 public:
  // Opens `path` for writing and writes the header. Throws std::runtime_error naming the path
  // when the file cannot be opened.
  CsvWriter(const std::string& path, std::vector<std::string> columns);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  // One row under construction; Write() checks the field count against the header.
  class Row {
   public:
    Row& operator<<(std::string_view text);
    Row& operator<<(const char* text) { return *this << std::string_view(text); }
    Row& operator<<(const std::string& text) { return *this << std::string_view(text); }
    Row& operator<<(double value);
    Row& operator<<(int value);
    Row& operator<<(long value);
    Row& operator<<(long long value);
    Row& operator<<(unsigned long value);
    Row& operator<<(bool value);

   private:
    friend class CsvWriter;
    std::vector<std::string> fields_;
  };

  // Writes the row as one line and flushes it.
  void Write(const Row& row);
  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
};

}  // namespace cb
