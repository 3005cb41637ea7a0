#!/usr/bin/env bash
# The readings study behind the "Readings of the report's figure" section of results/REPORT.md
# (docs/problems.md, "Other readings"; docs/findings.md). Each reading is a set of problem
# parameters of arch-flat (P2) and arch-curved (P3); for each it traces
#   RESULTS_DIR/readings/<reading>/arch-flat     P2, Newton, 2000 steps, limit and bifurcation
#                                                points detected and located (no branch switch)
#   RESULTS_DIR/readings/<reading>/arch-flat-qn  P2, quasi-Newton (for Table 1's counts: the
#                                                report's solver may be either)
#   RESULTS_DIR/readings/<reading>/arch-curved   P3, quasi-Newton (the report's Table 2 is of a
#                                                quasi-Newton solver), 1604 steps
# and, for the default reading of P2 only, the invariances of its kinks:
#   RESULTS_DIR/readings/invariance/<name>       the same 200 units of arc length with arc length
#                                                0.05 and 0.2, and in kN with E = 20 MPa
# RESULTS_DIR/readings/index.csv lists every run: reading, problem, solver, directory,
# settings, exit status. A run that fails keeps its records and the study goes on; the report says where the
# path stopped. Last, the records are thinned to what the report reads (about 8 MB of 66: the
# accepted steps, kinks, critical points and the iterations rescored at the report's stopping
# tests; results/thin_records.py), unless KEEP_FULL=1. results/plot.py then writes the section
# (results/plotlib/readings.py).
#
# Run time on the 2-core machine of results/README.md: about a minute (each run 1-3 s).
# Usage: scripts/run_readings.sh
# Environment: BUILD_DIR (default build/), RESULTS_DIR (default results/), QUICK=1 for 100 steps
# per run (a check of the pipeline, not a result), SKIP_SETUP=1 to use an existing build,
# KEEP_FULL=1 to keep every record (iterations.csv, states) instead of the thinned ones.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
out="${RESULTS_DIR:-$here/results}/readings"
if [[ "${SKIP_SETUP:-0}" != 1 ]]; then "$here/scripts/setup.sh" "$build" || exit 1; fi
cb="$build/bin/contactbench"
quick=(); [[ "${QUICK:-0}" == 1 ]] && quick=(--steps 100)

rm -rf "$out"
mkdir -p "$out"
index="$out/index.csv"
echo "reading,problem,solver,dir,settings,exit_status" >"$index"

run() {  # run READING PROBLEM SOLVER SUBDIR "KEY=VALUE ..."
  local reading="$1" problem="$2" solver="$3" subdir="$4" settings="$5"
  local dir="$out/$subdir"
  local sets=()
  for s in $settings; do sets+=(--set "$s"); done
  echo "== contactbench run --problem $problem ${sets[*]} --solver $solver --out $dir" >&2
  "$cb" run --problem "$problem" --formulation implicit-fb "${sets[@]}" --solver "$solver" \
      "${quick[@]}" --out "$dir" 2>>"$out/log.txt"
  local rc=$?
  echo "$reading,$problem,$solver,$subdir,\"$settings\",$rc" >>"$index"
}

# reading | P2 settings | P3 settings: scripts/readings.txt.
mapfile -t readings < <(grep -v -e '^#' -e '^$' "$here/scripts/readings.txt")
for entry in "${readings[@]}"; do
  IFS='|' read -r reading p2 p3 <<<"$entry"
  run "$reading" arch-flat newton "$reading/arch-flat" "$p2"
  run "$reading" arch-flat quasi-newton "$reading/arch-flat-qn" "$p2"
  run "$reading" arch-curved quasi-newton "$reading/arch-curved" "$p3"
done

# The default P2 path over the same 200 units of arc length at other arc lengths, and with the
# printed load unit (kN) at E = 20 MPa: the path depends only on load / (E A).
run arc-0.05 arch-flat newton invariance/arc-0.05 "arc_length=0.05 steps=4000"
run arc-0.2 arch-flat newton invariance/arc-0.2 "arc_length=0.2 steps=1000"
run kN-20MPa arch-flat newton invariance/kN-20MPa "load=5 youngs_modulus=2e4 force_scale=1"
# Thinned to what REPORT.md's section reads (results/thin_records.py): committed, so that
# results/plot.py on a fresh clone writes the section; KEEP_FULL=1 keeps every record.
if [[ "${KEEP_FULL:-0}" != 1 ]]; then
  /usr/bin/python3 "$here/results/thin_records.py" "$(dirname "$out")" readings || exit 1
fi
echo "records in $out (index.csv; run log: log.txt)" >&2
