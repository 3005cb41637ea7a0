#!/usr/bin/env bash
# CI job: builds the libFuzzer targets of fuzz/ (clang, -fsanitize=fuzzer,address,undefined) and
# runs each for a bounded time (FUZZ_SECONDS, default 30) from a seed corpus: the examples,
# fuzz/corpus/TARGET and every kept crash input in fuzz/regressions/. A crash, sanitizer report,
# timeout or out-of-memory fails the job; the input is left in BUILD_DIR/artifacts/ -- minimise
# it (TARGET -minimize_crash=1 -runs=10000 FILE), fix the reader, and keep it in
# fuzz/regressions/ (tests/fuzz_regressions_test.cc runs the readers on every file there).
# Usage: scripts/run_fuzz.sh [BUILD_DIR]   (default build-asan)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build-asan}"
seconds="${FUZZ_SECONDS:-30}"

# The instrumented build shared with scripts/check_sanitizers.sh (nothing to do when that ran).
"$here/scripts/sanitizer_build.sh" "$build" problem_file_fuzzer gmsh_fuzzer

export ASAN_OPTIONS="detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
mkdir -p "$build/artifacts"
status=0
for target in problem_file gmsh; do
  case $target in
    problem_file) pattern='*.json' ;;
    gmsh) pattern='*.msh' ;;
  esac
  # The working corpus grows across runs in the build directory; the seeds are read-only.
  work="$build/corpus/$target"
  seeds="$build/seeds/$target"
  mkdir -p "$work" "$seeds"
  find "$here/examples" -name "$pattern" -exec cp {} "$seeds/" \;
  [[ -d $here/fuzz/corpus/$target ]] && cp "$here/fuzz/corpus/$target/"* "$seeds/" 2>/dev/null
  cp "$here/fuzz/regressions/"* "$seeds/" 2>/dev/null || true
  echo "run_fuzz: $target for ${seconds}s (seeds: $(ls "$seeds" | wc -l) files)" >&2
  # -timeout: one input slower than 10 s is a hang; -rss_limit_mb and -malloc_limit_mb: an
  # input that makes a reader allocate 2 GB (a size field trusted before the data) is a finding.
  if ! "$build/bin/${target}_fuzzer" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=16384 -print_final_stats=1 \
      -dict="$here/fuzz/$target.dict" -artifact_prefix="$build/artifacts/$target-" \
      "$work" "$seeds" > "$build/$target.log" 2>&1; then
    status=1
    echo "run_fuzz: $target FAILED; the input is in $build/artifacts/:" >&2
    tail -n 60 "$build/$target.log" >&2
  else
    grep -E "^stat::number_of_executed_units|^stat::new_units_added" "$build/$target.log" \
      | sed "s/^/run_fuzz: $target: /" >&2 || true
  fi
done
exit $status
