#!/usr/bin/env bash
# CI job: the whole test suite (ctest) under AddressSanitizer with LeakSanitizer and
# UndefinedBehaviorSanitizer, in the instrumented build of scripts/sanitizer_build.sh. Any
# report fails the run: ASan and UBSan (halt_on_error, -fno-sanitize-recover) stop the test
# with an error, LeakSanitizer fails the process at exit.
# Usage: scripts/check_sanitizers.sh [BUILD_DIR]   (default build-asan; extra ctest arguments
# in CTEST_ARGS, e.g. CTEST_ARGS="-R Cli")
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build-asan}"

"$here/scripts/sanitizer_build.sh" "$build"

# detect_stack_use_after_return and check_initialization_order widen what ASan sees;
# strict_string_checks makes the C string functions check their whole arguments.
export ASAN_OPTIONS="detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# shellcheck disable=SC2086
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" ${CTEST_ARGS:-}
