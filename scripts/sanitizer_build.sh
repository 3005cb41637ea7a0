#!/usr/bin/env bash
# The one instrumented build that scripts/check_sanitizers.sh and scripts/run_fuzz.sh share:
# clang++ with AddressSanitizer (LeakSanitizer included), UndefinedBehaviorSanitizer and
# libFuzzer's coverage instrumentation (fuzzer-no-link: the tests link without libFuzzer, the
# fuzz targets add its main). One build instead of two keeps CI's time down on 2 cores.
# Debug at -O1: fast enough to run the whole suite, and Eigen's own assertions (eigen_assert)
# stay on; -fno-omit-frame-pointer gives usable stacks; -fno-sanitize-recover makes the first
# UBSan finding fatal. Warnings are the Release build's job (scripts/test.sh, -Werror).
# Usage: scripts/sanitizer_build.sh BUILD_DIR [TARGET...]   (no target: all)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$1"
shift

"$here/scripts/install_packages.sh" sanitize  # scripts/packages.txt

# No Python module here: an instrumented extension loads only into a Python started with the
# sanitizer runtime preloaded; the module's tests run in the Release build (docs/python.md).
# PETSc and Siconos are built as their stubs here even when their packages are installed (the
# test job installs them first): Open MPI's and Siconos's allocations kept until exit would
# swamp LeakSanitizer with reports that are not ours (docs/hardening.md).
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined"
flags+=" -fno-omit-frame-pointer"
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCONTACTBENCH_FUZZ=ON -DBUILD_BENCHMARKS=OFF -DCONTACTBENCH_PYTHON=OFF \
  -DCONTACTBENCH_WITH_PETSC=OFF -DCONTACTBENCH_WITH_SICONOS=OFF >/dev/null
if (($#)); then
  cmake --build "$build" -j"$(nproc)" --target "$@"
else
  cmake --build "$build" -j"$(nproc)"
fi
