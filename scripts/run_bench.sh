#!/usr/bin/env bash
# The standard benchmark set: builds (scripts/setup.sh, Release) and runs the Google Benchmark
# binaries, writing Google Benchmark's own JSON to RESULTS_DIR/bench/<binary>.json (default
# results/bench/), and the console tables to <binary>.txt beside it.
#
#   implicit_fb_benchmark        the implicit smoothed-FB timings (P1 per linear solver, P3 step,
#                                whole paths, Newton iteration / factorisation)
#   formulation_step_benchmark   one replayed P2 / P3 step per formulation x start x step
#   scaling_benchmark            P1 cold solve, n = 25 ... 400, every fixed-load formulation
#   speed_floor_benchmark        P1 n = 100 ... 400 and hertz-3d n = 16 ... 40 cold, implicit-fb's
#                                time split and floor against its full route and PETSc's best
#
# Repetitions: 3 (aggregates only: mean, median, stddev, cv, and the min and max every binary
# adds, so each time is a median with its range), except where a benchmark fixes its own
# (solves of seconds are measured once, one sample with no range; see each binary's header
# comment). The JSON's context holds the load average at the start (Google Benchmark's
# load_avg); this script adds load_avg_end, read when the binary has finished, the commit of the
# build (contactbench_commit) and the binary's wall time (wall_time_s).
# Run time on the 2-core machine of results/README.md, measured on the quiet machine: 16 minutes
# (implicit_fb_benchmark 469 s, formulation_step_benchmark 255 s, scaling_benchmark 228 s).
# Usage: scripts/run_bench.sh [extra Google Benchmark flags, e.g. --benchmark_filter=...]
# Environment: BUILD_DIR (default build/), RESULTS_DIR (default results/), REPETITIONS (3),
# SKIP_SETUP=1 to use an existing build without running setup.sh.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
out="${RESULTS_DIR:-$here/results}/bench"
repetitions="${REPETITIONS:-3}"
if [[ "${SKIP_SETUP:-0}" != 1 ]]; then "$here/scripts/setup.sh" "$build" || exit 1; fi
mkdir -p "$out"

status=0
for binary in implicit_fb_benchmark formulation_step_benchmark scaling_benchmark \
  speed_floor_benchmark; do
  exe="$build/bin/$binary"
  if [[ ! -x "$exe" ]]; then
    echo "run_bench: $exe not built (BUILD_BENCHMARKS=OFF?)" >&2; status=1; continue
  fi
  echo "== $binary -> $out/$binary.json" >&2
  start=$SECONDS
  run=("$exe" --benchmark_repetitions="$repetitions" --benchmark_report_aggregates_only=true
       --benchmark_out="$out/$binary.json" --benchmark_out_format=json "$@")
  if [[ -t 2 ]]; then
    # On a terminal the console table also goes to the screen as each benchmark finishes (the
    # progress of a run of minutes); otherwise only to the .txt file.
    "${run[@]}" | tee "$out/$binary.txt" >&2
    rc=${PIPESTATUS[0]}
  else
    "${run[@]}" > "$out/$binary.txt"
    rc=$?
  fi
  ((rc == 0)) || { echo "   ($binary failed)" >&2; status=1; }
  if [[ -s "$out/$binary.json" ]]; then
    commit=$("$build/bin/contactbench" --version 2>/dev/null | sed -n 's/.*(commit \(.*\)).*/\1/p')
    python3 - "$out/$binary.json" "${commit:-unknown}" "$((SECONDS - start))" <<'PY' || status=1
import json
import os
import sys
path, commit, wall = sys.argv[1], sys.argv[2], int(sys.argv[3])
with open(path) as f:
    report = json.load(f)
report["context"]["load_avg_end"] = list(os.getloadavg())
# The build the binary came from (the contactbench beside it) and the run's wall time: REPORT.md's
# table of the records' commits and run times reads them (results/plotlib/provenance.py).
report["context"]["contactbench_commit"] = commit
report["context"]["wall_time_s"] = wall
with open(path + ".tmp", "w") as f:
    json.dump(report, f, indent=2)
os.replace(path + ".tmp", path)
PY
  fi
  echo "   $((SECONDS - start)) s" >&2
done
exit $status
