#!/usr/bin/env bash
# Installs whatever Debian packages are missing, then configures and builds contactbench.
# Usage: scripts/setup.sh [BUILD_DIR] [extra cmake arguments...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
shift || true

packages=(cmake g++ ninja-build pkg-config libeigen3-dev coinor-libipopt-dev libnlopt-cxx-dev
          libsuitesparse-dev libgtest-dev libbenchmark-dev python3-matplotlib python3-pandas
          python3-numpy nlohmann-json3-dev)
"$here/scripts/install_packages.sh" "${packages[@]}"

cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCONTACTBENCH_WERROR=ON "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
