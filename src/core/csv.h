// Long-format CSV records, written and flushed row by row so that a run that stops early
// keeps every complete line (docs/architecture.md, house rule 7). A failed or short write (a
// full disk, a file size limit) cuts the file back to its last whole line and throws
// WriteError: a truncated number still parses, so a half line must never stay.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cb {

// Formats a double in the shortest form that reads back to the same value ("nan", "inf").
std::string FormatDouble(double value);
// FormatDouble, marked as a real number when it would read as an integer ("1" -> "1.0",
// "-0" -> "-0.0"), so that a CSV column of doubles has one type in every file, whatever its
// values (a reader infers int64 from "1" and float64 from "0.5").
std::string FormatReal(double value);

// A record file could not be written completely; `path()` names it. The file holds only whole
// lines (or nothing).
class WriteError : public std::runtime_error {
 public:
  WriteError(const std::string& path, const std::string& reason)
      : std::runtime_error("cannot write '" + path + "': " + reason), path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class CsvWriter {
 public:
  // Opens `path` for writing and writes the header. Throws std::runtime_error naming the path
  // when the file cannot be opened, WriteError when the header cannot be written. With
  // `memory`, no file is opened: the same lines go to *memory (emptied first), and `path` only
  // names the records (the Python module's records without an output directory).
  CsvWriter(const std::string& path, std::vector<std::string> columns,
            std::string* memory = nullptr);
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

  // Writes the row as one line, unbuffered. On a failed or short write, cuts the file back to
  // its last whole line and throws WriteError.
  void Write(const Row& row);
  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::string* memory_ = nullptr;
  int fd_ = -1;
  long long whole_lines_bytes_ = 0;  // the file's length up to its last whole line
};

}  // namespace cb
