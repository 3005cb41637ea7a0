#!/usr/bin/env bash
# Writes the records that a change of structure or speed must leave unchanged: the P1 solve
# (cold, dogleg and Newton; near the solution), 400 steps of P2 and 1000 through its limit and
# bifurcation points with a branch switch, 400 steps of P3 (implicit-fb) and 200 (active-set),
# the two-bar truss onto its floor with theta = 0.2 by nonsmooth-fb and active-set (step 3
# stalls and takes the restart of formulations/nonsmooth/nonsmooth_restart.h, then verifies),
# and a replay comparison on the two-bar truss with an obstacle. Compare two such directories
# with scripts/diff_records.py.
# Usage: scripts/reference_records.sh CONTACTBENCH_BINARY OUT_DIR
set -euo pipefail
cb="$1"
out="$2"
logs="$out.logs"  # beside, not inside: the logs hold wall times
rm -rf "$out" "$logs"
mkdir -p "$out" "$logs"
run() {  # run SUBDIR ARGS...
  local dir="$out/$1"
  "$cb" run "${@:2}" --out "$dir" >/dev/null 2>"$logs/$1" || echo "exit $?" >>"$logs/$1"
}
run p1-dogleg --problem block --formulation implicit-fb --start cold --solver dogleg --eta 1
run p1-newton --problem block --formulation implicit-fb --start cold --solver newton --eta 2
run p2 --problem arch-flat --formulation implicit-fb --steps 400 --bifurcations switch \
  --save-every 100
run p2-switch --problem arch-flat --formulation implicit-fb --steps 1000 --bifurcations switch \
  --save-every 250
run p1-near --problem block --formulation implicit-fb --start near --solver newton --eta 3
run p3 --problem arch-curved --formulation implicit-fb --steps 400 --save-every 200
run p3-active-set --problem arch-curved --formulation active-set --steps 200
run restart-fb --problem two-bar-obstacle --formulation nonsmooth-fb --arc-length 0.2
run restart-min --problem two-bar-obstacle --formulation active-set --arc-length 0.2
"$cb" compare --problem two-bar-obstacle --formulations implicit-fb,nonsmooth-fb,active-set,ipopt-mpcc --steps 60 --out "$out/compare" >/dev/null 2>"$logs/compare" ||
  echo "exit $?" >>"$logs/compare"
