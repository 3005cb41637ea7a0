// The documentation of the record files, produced from their schemas (record_schemas.h): the
// generated section of docs/records.md, printed by `contactbench schema`.
#pragma once

#include <string>

namespace cb::harness {

// Markdown: per record file a heading, what one row is, which subcommands write it, and a
// table of its columns in order.
std::string RecordsMarkdown();

}  // namespace cb::harness
