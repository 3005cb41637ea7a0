// The schema of a record file: one table of columns {name, meaning, value}, from which the CSV
// header, every row and the documentation (docs/records.md) are produced, so that the three
// cannot disagree. A column's value is a function of the row's data (`Data`, one struct per
// record file, record_schemas.h); it yields a Cell, formatted as CsvWriter formats its type.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "core/csv.h"

namespace cb::harness {

// One field's value: text, a double (shortest round-trip form, always read back as a real), an
// integer or a bool
// ("true"/"false"). Other types are refused at compile time rather than silently converted.
class Cell {
 public:
  Cell(std::string text) : value_(std::move(text)) {}
  Cell(std::string_view text) : value_(std::string(text)) {}
  Cell(const char* text) : value_(std::string(text)) {}
  Cell(double value) : value_(value) {}
  Cell(int value) : value_(value) {}
  Cell(std::int64_t value) : value_(value) {}
  Cell(bool value) : value_(value) {}
  template <typename T>
  Cell(T) = delete;

  void AppendTo(CsvWriter::Row* row) const {
    std::visit([row](const auto& value) { *row << value; }, value_);
  }

 private:
  std::variant<std::string, double, int, std::int64_t, bool> value_;
};

template <typename Data>
struct Column {
  const char* name;
  const char* meaning;  // markdown
  Cell (*value)(const Data&);
  bool only_3d = false;  // written only for a three-dimensional body
};

// A column as the documentation sees it (whatever the row's data).
struct ColumnDoc {
  std::string name;
  std::string meaning;
  bool only_3d = false;
};

// A record file as the documentation sees it.
struct RecordDoc {
  std::string file;                     // "steps.csv"
  std::string variant;                  // "" or the kind of problem this layout is for
  std::string one_row_per;              // what one row is (markdown)
  std::vector<std::string> written_by;  // the subcommands that write the file
  std::vector<ColumnDoc> columns;
};

// Written for every body, or only for a three-dimensional one.
inline bool ColumnWritten(bool only_3d, int dimension) { return !only_3d || dimension == 3; }

template <typename Data>
struct RecordSchema {
  std::string file;
  std::string variant;
  std::string one_row_per;
  std::vector<std::string> written_by;
  std::vector<Column<Data>> columns;

  // The header of the file for a body of dimension `dimension` (0: no body).
  std::vector<std::string> Header(int dimension) const {
    std::vector<std::string> names;
    for (const auto& c : columns) {
      if (ColumnWritten(c.only_3d, dimension)) names.push_back(c.name);
    }
    return names;
  }

  CsvWriter::Row RowOf(const Data& data, int dimension) const {
    CsvWriter::Row row;
    for (const auto& c : columns) {
      if (ColumnWritten(c.only_3d, dimension)) c.value(data).AppendTo(&row);
    }
    return row;
  }

  RecordDoc Doc() const {
    RecordDoc doc{file, variant, one_row_per, written_by, {}};
    for (const auto& c : columns) doc.columns.push_back({c.name, c.meaning, c.only_3d});
    return doc;
  }
};

// Where the record files go: the files of an output directory, or (the Python module without
// an output directory, docs/python.md) their texts in memory by file name ("steps.csv"), the
// same bytes the files would hold.
struct RecordTarget {
  RecordTarget(std::string dir) : directory(std::move(dir)) {}
  RecordTarget(const char* dir) : directory(dir) {}
  explicit RecordTarget(std::map<std::string, std::string>* texts) : memory(texts) {}

  std::string directory;
  std::map<std::string, std::string>* memory = nullptr;
};

// A record file open for writing: DIR/<schema.file> with the schema's header, one row per
// Write (flushed at once, as CsvWriter does).
template <typename Data>
class RecordWriter {
 public:
  RecordWriter(const RecordTarget& target, const RecordSchema<Data>& schema, int dimension = 0)
      : schema_(schema),
        dimension_(dimension),
        csv_(target.directory + "/" + schema.file, schema.Header(dimension),
             target.memory ? &(*target.memory)[schema.file] : nullptr) {}

  void Write(const Data& data) { csv_.Write(schema_.RowOf(data, dimension_)); }

 private:
  const RecordSchema<Data>& schema_;
  int dimension_;
  CsvWriter csv_;
};

}  // namespace cb::harness
