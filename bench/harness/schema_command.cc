#include <iostream>

#include "harness/cli.h"
#include "harness/cli_commands.h"
#include "harness/records_doc.h"

namespace cb::harness {

// Prints the record files' columns (docs/records.md's generated section).
int SchemaCommand() {
  std::cout << RecordsMarkdown();
  return kExitOk;
}

}  // namespace cb::harness
