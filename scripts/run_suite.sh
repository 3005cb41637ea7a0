#!/usr/bin/env bash
# The main job: set up (install, build), then run the suite on the report's examples and write
# results/ (CSV records per run, and results/SUMMARY.md generated from them).
# A run that fails keeps its records and the job goes on; the summary says what failed.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
out="${RESULTS_DIR:-$here/results}"
"$here/scripts/setup.sh" "$build" || exit 1
cb="$build/bin/contactbench"

status=0
run() {  # run OUT_SUBDIR ARGS...
  local dir="$out/$1"; shift
  echo "== contactbench run $* --out $dir" >&2
  "$cb" run "$@" --out "$dir"
  local rc=$?
  if ((rc != 0)); then echo "   (exit status $rc: records kept in $dir)" >&2; status=3; fi
}

# P1 block (report 5.1): the single fixed-load solve from the cold start, eta cases 1-4, with
# the trust-region dogleg solver the report used and with Newton.
for solver in dogleg newton; do
  for eta in 1 2 3 4; do
    run "block/eta$eta-$solver" --problem block --formulation implicit-fb --start cold \
        --solver "$solver" --eta "$eta"
  done
done
# P2 arch-flat and P3 arch-curved (report 5.2, 5.3): the arc-length paths, Newton and the
# quasi-Newton solver, kinks located.
for problem in arch-flat arch-curved; do
  for solver in newton quasi-newton; do
    run "$problem/$solver" --problem "$problem" --formulation implicit-fb --solver "$solver"
  done
done

# Every arc-length-capable formulation on the same 200 P3 steps (replay mode), warm and cold
# (issue 3); a step may take at most 5 s (dense SLSQP is the slow one).
echo "== contactbench compare --problem arch-curved (200 steps, warm and cold)" >&2
"$cb" compare --problem arch-curved --starts warm,cold --steps 200 --time-limit 5 \
    --out "$out/compare/arch-curved" || status=3

/usr/bin/python3 "$here/results/summarize.py" "$out" > "$out/SUMMARY.md" && echo "wrote $out/SUMMARY.md" >&2
exit $status
