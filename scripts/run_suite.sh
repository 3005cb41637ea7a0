#!/usr/bin/env bash
# The main job: set up (install, build), then regenerate results/:
#   results/block/, arch-flat/, arch-curved/   the report's three examples: records
#                                              (CSV), saved states (CSV, VTK)
#   results/readings/                          P2 and P3 under other readings of the report's
#                                              figure (scripts/run_readings.sh, about a minute)
#   results/solid3d/                           hertz-3d's meshes and plate-3d's path
#                                              (scripts/run_solid3d.sh, about a minute)
#   results/compare/                           the formulation comparison (scripts/run_compare.sh)
#   results/bench/                             the benchmark binaries' JSON (scripts/run_bench.sh)
#   results/figures/, REPORT.md, COMPARISON.md from those CSV/JSON files by results/plot.py
# A run that fails keeps its records and the job goes on; the reports say what failed.
# Usage: scripts/run_suite.sh
# Environment:
#   BUILD_DIR=DIR    the build to set up and run (default build/)
#   RESULTS_DIR=DIR  where the records, figures and reports go (default results/, the committed
#                    run: give another directory to keep it as it is)
#   SKIP_SETUP=1     neither install nor build: run the contactbench already built in BUILD_DIR
#   SKIP_READINGS=1, SKIP_SOLID3D=1, SKIP_COMPARE=1, SKIP_BENCH=1 leave those parts (and their
#                    old files) alone
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
out="${RESULTS_DIR:-$here/results}"
if [[ "${SKIP_SETUP:-0}" != 1 ]]; then "$here/scripts/setup.sh" "$build" || exit 1; fi
cb="$build/bin/contactbench"
if [[ ! -x $cb ]]; then
  echo "run_suite: no $cb (SKIP_SETUP=1 needs a build in BUILD_DIR)" >&2
  exit 1
fi
mkdir -p "$out"

status=0
run() {  # run OUT_SUBDIR ARGS...
  local dir="$out/$1"; shift
  rm -rf "$dir"
  echo "== contactbench run $* --out $dir" >&2
  "$cb" run "$@" --out "$dir"
  local rc=$?
  if ((rc != 0)); then echo "   (exit status $rc: records kept in $dir)" >&2; status=3; fi
}

# P1 block (report 5.1): the single fixed-load solve from the cold start, eta cases 1-4, with
# the trust-region dogleg solver the report used and with Newton; case 3 also from a start near
# the solution (the implicit-fb solution perturbed by 1%), as the report did.
for solver in dogleg newton; do
  for eta in 1 2 3 4; do
    run "block/eta$eta-$solver" --problem block --formulation implicit-fb --start cold \
        --solver "$solver" --eta "$eta"
  done
  run "block/eta3-near-$solver" --problem block --formulation implicit-fb --start near \
      --solver "$solver" --eta 3
done
# P2 arch-flat (report 5.2): through the limit point B and the bifurcation point C, switching
# onto the asymmetric branch D; P3 arch-curved (report 5.3): the report's 1604 steps. Newton and
# the quasi-Newton solver; kinks located; a state saved every 100 steps and at critical points.
for solver in newton quasi-newton; do
  run "arch-flat/$solver" --problem arch-flat --formulation implicit-fb --solver "$solver" \
      --bifurcations switch --save-every 100
  run "arch-curved/$solver" --problem arch-curved --formulation implicit-fb --solver "$solver" \
      --save-every 200
done

if [[ "${SKIP_READINGS:-0}" != 1 ]]; then
  SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$out" "$here/scripts/run_readings.sh" || status=3
fi
if [[ "${SKIP_SOLID3D:-0}" != 1 ]]; then
  SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$out" "$here/scripts/run_solid3d.sh" || status=3
fi
if [[ "${SKIP_COMPARE:-0}" != 1 ]]; then
  SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$out" "$here/scripts/run_compare.sh" || status=3
fi
if [[ "${SKIP_BENCH:-0}" != 1 ]]; then
  SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$out" "$here/scripts/run_bench.sh" || status=3
fi

/usr/bin/python3 "$here/results/plot.py" "$out" || status=3
exit $status
