#!/usr/bin/env bash
# Regenerates the section of docs/records.md between its BEGIN and END markers from the record
# schemas (bench/harness/record_schemas.cc): the output of `contactbench schema`.
# Usage: scripts/update_records_doc.sh CONTACTBENCH_BINARY
set -euo pipefail
cb="$1"
doc="$(dirname "$0")/../docs/records.md"
tables="$(mktemp)"
trap 'rm -f "$tables" "$doc.tmp"' EXIT
"$cb" schema >"$tables"
awk -v tables="$tables" '
  /^<!-- BEGIN contactbench schema -->$/ {
    print
    while ((getline line < tables) > 0) print line
    skip = 1
    next
  }
  /^<!-- END contactbench schema -->$/ { skip = 0 }
  !skip { print }
' "$doc" >"$doc.tmp"
mv "$doc.tmp" "$doc"
