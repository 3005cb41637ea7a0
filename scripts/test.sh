#!/usr/bin/env bash
# The test command: set up (install, build) and run the whole test suite.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
"$here/scripts/setup.sh" "$build"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
