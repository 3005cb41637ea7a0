#!/usr/bin/env bash
# Installs whatever Debian packages the build needs are missing (scripts/packages.txt), then
# configures and builds contactbench.
# Usage: scripts/setup.sh [BUILD_DIR] [extra cmake arguments...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
shift || true

"$here/scripts/install_packages.sh" build  # scripts/packages.txt

cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCONTACTBENCH_WERROR=ON "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
