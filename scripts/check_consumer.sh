#!/usr/bin/env bash
# CI: the library as a CMake package. Installs the build (default build/, or BUILD_DIR) to a
# temporary prefix, checks the installed package config, then configures, builds and runs
# examples/consumer against it: a program that finds the package, includes <contactbench/...>,
# loads a problem file and traces its path. Fails on any step.
# Usage: scripts/check_consumer.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-${BUILD_DIR:-$here/build}}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

cmake --build "$build" --target contactbench >/dev/null
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
config="$(find "$tmp/prefix" -name contactbenchConfig.cmake)"
if grep -nE '^\s*if\((ON|OFF|TRUE|FALSE|1|0)\)' "$config"; then
  echo "check_consumer: $config tests a literal constant" >&2
  exit 1
fi
test -f "$tmp/prefix/include/contactbench/path/path.h"
test -f "$tmp/prefix/include/contactbench/formulations/registry.h"

launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$here/examples/consumer" -B "$tmp/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_CXX_FLAGS="-Wall -Wextra -Werror" "${launcher[@]}" \
  >/dev/null
cmake --build "$tmp/consumer" >/dev/null
"$tmp/consumer/trace_problem" "$here/examples/truss-2d-bar-wall.json" >"$tmp/trace.txt"
tail -n 1 "$tmp/trace.txt"
grep -q "^truss-2d-bar-wall: .*(40 accepted steps, 1 kinks)$" "$tmp/trace.txt"
echo "check_consumer: the installed package builds and runs examples/consumer" >&2
