#!/usr/bin/env bash
# CI: the library as a CMake package. Installs the build (default build/, or BUILD_DIR) to a
# temporary prefix, checks the installed package config, then configures, builds and runs
# examples/consumer against it: a program that finds the package, includes <contactbench/...>,
# loads a problem file and traces its path; and the backends as components (asked for, had and
# lacked). Fails on any step.
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

# The optional backends as components. A consumer that requires one the build has finds the
# package; one that requires one the build lacks, or one no build has, gets "not found" with
# the reason at configure time (not a link error later); OPTIONAL_COMPONENTS of a lacking one
# finds the package with contactbench_<component>_FOUND false.
probe() {  # probe "<find_package arguments after the version>": configures a one-line consumer
  mkdir -p "$tmp/probe"
  printf '%s\n' "cmake_minimum_required(VERSION 3.25)" "project(probe LANGUAGES CXX)" \
    "find_package(contactbench 0.1 $1)" \
    'message(STATUS "probe: found=${contactbench_FOUND} component=${contactbench_${component}_FOUND}")' \
    >"$tmp/probe/CMakeLists.txt"
  rm -rf "$tmp/probe/build"
  cmake -S "$tmp/probe" -B "$tmp/probe/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
    -Dcomponent="${2:-none}" >"$tmp/probe.log" 2>&1
}
fail() {
  echo "check_consumer: $1" >&2
  cat "$tmp/probe.log" >&2
  exit 1
}
mapfile -t components < <(sed -n 's/^set(contactbench_\([a-z]*\)_FOUND \(ON\|OFF\))$/\1 \2/p' "$config")
((${#components[@]} == 4)) || fail "the config does not list the four backends as components"
lacking=0
for entry in "${components[@]}"; do
  read -r name built <<<"$entry"
  if [[ $built == ON ]]; then
    probe "REQUIRED COMPONENTS $name" || fail "requiring $name, which the build has, failed"
    continue
  fi
  lacking=$((lacking + 1))
  if probe "REQUIRED COMPONENTS $name"; then fail "requiring $name, which the build lacks, passed"; fi
  grep -q "built without its $name backend" "$tmp/probe.log" || fail "no reason given for $name"
  probe "OPTIONAL_COMPONENTS $name" "$name" || fail "an optional $name, lacking, failed"
  grep -qE "probe: found=(1|TRUE) component=OFF" "$tmp/probe.log" || fail "an optional $name: not OFF"
done
if probe "REQUIRED COMPONENTS no_such_backend"; then fail "an unknown component passed"; fi
grep -q "has no component 'no_such_backend'" "$tmp/probe.log" || fail "no reason given"
echo "check_consumer: components ${components[*]} (the build lacks $lacking)" >&2

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

# examples/plugin: a formulation compiled on its own against the installed package, loaded by
# the installed driver with --plugin and compared beside a built-in one (docs/your-own-method.md).
cmake -S "$here/examples/plugin" -B "$tmp/plugin" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_CXX_FLAGS="-Wall -Wextra -Werror" "${launcher[@]}" \
  >/dev/null
cmake --build "$tmp/plugin" >/dev/null
"$tmp/prefix/bin/contactbench" compare --plugin "$tmp/plugin/libmin_newton.so" --problem arch-flat \
  --formulations min-newton,active-set --starts warm --steps 4 --out "$tmp/plugin-compare" 2>/dev/null
grep -q "^arch-flat,min-newton,.*,converged," "$tmp/plugin-compare/runs.csv"
echo "check_consumer: the installed package builds examples/plugin and the driver compares it" >&2
