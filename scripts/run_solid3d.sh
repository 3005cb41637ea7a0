#!/usr/bin/env bash
# The 3-D solids behind the "Three-dimensional solids" section of results/REPORT.md
# (docs/problems.md, "Three-dimensional solids and `hertz-3d`"):
#   RESULTS_DIR/solid3d/hertz/n<N>/   hertz-3d on N x N x N hexahedra, N = 4 8 12 16 20 24:
#                                     the fixed-load solve by implicit-fb (Newton), for the
#                                     convergence table against Hertz's closed form
#   RESULTS_DIR/solid3d/plate-3d/     plate-3d's 200 arc-length steps by implicit-fb, kinks
#                                     located, a state saved every 50 steps
# RESULTS_DIR/solid3d/index.csv lists every run: name, directory, exit status. A run that fails
# keeps its records and the script goes on. Last, the records are thinned to what the report
# reads (about 1 MB of 25: no states, cells or VTK files of the meshes; results/thin_records.py),
# unless KEEP_FULL=1; results/plot.py then writes the section (results/plotlib/solid3d.py).
#
# Run time on the 2-core machine of results/README.md: about a minute (24^3: d = 45 625, ~20 s).
# Usage: scripts/run_solid3d.sh
# Environment: BUILD_DIR (default build/), RESULTS_DIR (default results/), QUICK=1 for the
# meshes 4 and 8 and 40 steps of the plate (a check of the pipeline, not a result),
# SKIP_SETUP=1 to use an existing build, KEEP_FULL=1 to keep every record.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
out="${RESULTS_DIR:-$here/results}/solid3d"
if [[ "${SKIP_SETUP:-0}" != 1 ]]; then "$here/scripts/setup.sh" "$build" || exit 1; fi
cb="$build/bin/contactbench"
sizes=(4 8 12 16 20 24)
plate=()
if [[ "${QUICK:-0}" == 1 ]]; then sizes=(4 8); plate=(--steps 40); fi

rm -rf "$out"
mkdir -p "$out"
index="$out/index.csv"
echo "name,dir,exit_status" >"$index"
status=0

run() {  # run NAME SUBDIR ARGS...
  local name="$1" subdir="$2"; shift 2
  echo "== contactbench run $* --out $out/$subdir" >&2
  "$cb" run "$@" --formulation implicit-fb --out "$out/$subdir" 2>>"$out/log.txt"
  local rc=$?
  echo "$name,$subdir,$rc" >>"$index"
  if ((rc != 0)); then echo "   (exit status $rc: records kept)" >&2; status=3; fi
}

for n in "${sizes[@]}"; do
  run "hertz-3d n=$n" "hertz/n$n" --problem hertz-3d --set "n=$n" --set "nz=$n"
done
run plate-3d plate-3d --problem plate-3d --save-every 50 "${plate[@]}"
# Thinned to what REPORT.md's section reads (results/thin_records.py): committed, so that
# results/plot.py on a fresh clone writes the section; KEEP_FULL=1 keeps every record.
if [[ "${KEEP_FULL:-0}" != 1 ]]; then
  /usr/bin/python3 "$here/results/thin_records.py" "$(dirname "$out")" solid3d || exit 1
fi
echo "records in $out (index.csv; run log: log.txt)" >&2
exit $status
