#include "harness/records_doc.h"

#include "harness/record_schemas.h"

namespace cb::harness {

namespace {

std::string Section(const RecordDoc& doc) {
  std::string text = "### `" + doc.file + "`";
  if (!doc.variant.empty()) text += " (" + doc.variant + ")";
  text += "\n\nOne row per " + doc.one_row_per + ". Written by ";
  for (std::size_t k = 0; k < doc.written_by.size(); ++k) {
    if (k > 0) text += " and ";
    text += "`contactbench " + doc.written_by[k] + "`";
  }
  text += ".\n\n| column | meaning |\n|---|---|\n";
  for (const ColumnDoc& c : doc.columns) {
    text += "| `" + c.name + "` | " + c.meaning + (c.only_3d ? " (3-D bodies only)" : "") + " |\n";
  }
  return text;
}

}  // namespace

std::string RecordsMarkdown() {
  std::string text;
  for (const RecordDoc& doc : RecordDocs()) {
    if (!text.empty()) text += '\n';
    text += Section(doc);
  }
  return text;
}

}  // namespace cb::harness
