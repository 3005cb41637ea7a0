#!/usr/bin/env bash
# The summary check of the comparison sets (docs/findings.md, "Reproduction check"): the sets
# behind COMPARISON.md take about an hour, so instead of rerunning them it replays the first
# FULL_STEPS (default 100) steps of the sets arch-flat and arch-curved and the whole of block
# (scripts/run_compare.sh, as the quick mode of the main job does; about 40 s) into a temporary
# directory, and compares with the committed sets over the same steps by
# scripts/diff_comparison.py: per formulation x start the verified steps and the median iterations,
# as COMPARISON.md's tables aggregate them (time-limited solves aside). The prefix and step-size
# sets and the benchmarks are not replayed. Nothing is written outside the temporary directory.
#
# Usage: scripts/check_comparison.sh
# Environment: BUILD_DIR (default build/: its contactbench is run, nothing is built), FULL_STEPS
# (100), KEEP_DIR=DIR keeps the replay's records in DIR (new or empty) instead of a temporary
# directory. Exit status 1 when a set differs, 2 on a usage error.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if (($#)); then echo "usage: scripts/check_comparison.sh (no arguments)" >&2; exit 2; fi
build="${BUILD_DIR:-$here/build}"
if [[ ! -x $build/bin/contactbench ]]; then
  echo "check_comparison: no $build/bin/contactbench (build first, or give BUILD_DIR)" >&2
  exit 2
fi
if [[ -n "${KEEP_DIR:-}" ]]; then
  tmp="$KEEP_DIR"
  if [[ -n "$(ls -A "$tmp" 2>/dev/null)" ]]; then
    echo "check_comparison: KEEP_DIR $tmp is not empty" >&2; exit 2
  fi
  mkdir -p "$tmp"
else
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/contactbench-check-comparison.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
fi
start=$SECONDS
SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$tmp/results" FULL_STEPS="${FULL_STEPS:-100}" \
  "$here/scripts/run_compare.sh" arch-flat arch-curved block >"$tmp/log.txt" 2>&1
echo "check_comparison: replayed arch-flat and arch-curved (${FULL_STEPS:-100} steps) and block" \
     "in $((SECONDS - start)) s (log: $tmp/log.txt)" >&2
/usr/bin/python3 "$here/scripts/diff_comparison.py" "$here/results" "$tmp/results"
status=$?
if ((status == 1)); then
  echo "check_comparison: FAILED: the code no longer gives the committed comparison sets" \
       "(above); regenerate them (scripts/run_compare.sh, about an hour) and say in the commit" \
       "what moved and why" >&2
fi
exit $status
