#!/usr/bin/env bash
# The comparison runs (`contactbench compare`, replay mode; docs/comparison.md) behind
# results/COMPARISON.md. Records go to RESULTS_DIR/compare/<set>/ (default results/compare/):
#
#   arch-flat, arch-curved   P2 and P3, the FULL default path of each problem (its `steps`
#                            parameter: 2000 and 1604 steps unless the problem's defaults change),
#                            every available formulation except the two slow NLopt ones, warm and
#                            cold; those that cannot express an arc-length step are listed as
#                            skipped.
#   arch-flat-prefix, arch-curved-prefix
#                            the first PREFIX_STEPS (default 50) steps of the same paths with
#                            every formulation INCLUDING nlopt-mpcc and nlopt-merit, the two left
#                            out of the full paths: dense SLSQP takes 1-5 s per P3 step against
#                            0.1 ms for implicit-fb, and LBFGS on the merit ~2.6 s per P2 step
#                            (it stops at its evaluation limit without verifying a step), so
#                            each would need hours on the full paths, warm and cold.
#   block                    P1 (n = 50, the report's mesh), the single fixed-load solve from the
#                            cold start, every available formulation (nlopt-mpcc refuses it:
#                            dense above 2000 unknowns, recorded as skipped). Cold only: a
#                            "warm" start of the one solve from the unloaded state would be
#                            u = 0, r = 0, which is no previous answer.
#   robustness               robustness against the step size: P2 and P3 replayed at each arc
#                            length theta of ROBUST_THETAS (default 0.1 0.2 0.5 1.0), each theta
#                            a reference path of its own over the same stretch of arc length
#                            (ROBUST_ARC_FLAT = 100 for P2, through its limit point B at arc
#                            length ~91; ROBUST_ARC_CURVED = 50 for P3, through its first
#                            nonsmooth limit point at ~46), so round(arc / theta) steps: 1000,
#                            500, 200, 100 on P2 and 500, 250, 100, 50 on P3. Warm start, the
#                            formulations of the full paths. Records go to
#                            RESULTS_DIR/robustness/<problem>/theta-<theta>/.
#   fclib                    opt-in (not among the default sets): the problem set of the FCLIB
#                            files in FCLIB_DIR (default tests/data/fclib, the five committed
#                            Siconos files), read with friction dropped (mu = 0), every available
#                            formulation on every file, cold and from each file's guesses, each
#                            solve repeated FCLIB_REPEAT times (default 5); `compare
#                            --problem-dir`, records in problems.csv (docs/comparison.md
#                            "Problem sets").
#
# Timings (docs/comparison.md "Timing protocol"): block's single solve is repeated BLOCK_REPEAT
# times (default 5; compare --repeat) and recorded as the median with its min and max; a path's
# thousands of steps are timed once each (their spread is the spread over the steps).
# Every solve has a time limit of TIME_LIMIT seconds (default 5, as the main job's comparison);
# runs.csv records it (column time_limit_s), and the report charges failures at it.
# Problem parameters are the builders' defaults, whatever they are when this runs: nothing here
# depends on the reconstruction choices.
#
# Run time on the 2-core machine of results/README.md, which gives each set's: 62.5 minutes for the
# committed sets, on a machine loaded by other jobs (load 4-8). Before the peers and the
# step-size set joined, the five other sets took 28.5 minutes (with run_bench.sh busy on the
# other core for the first 22): arch-flat 246 s, arch-curved 425 s, arch-flat-prefix 215 s,
# arch-curved-prefix 818 s (~550 s nlopt-mpcc, ~250 s nlopt-merit), block 6 s.
# Usage: scripts/run_compare.sh [SET ...]   (default: all six sets, in the order above)
# Environment: BUILD_DIR (default build/), RESULTS_DIR (default results/), TIME_LIMIT (5),
# BLOCK_REPEAT (5), FCLIB_DIR (tests/data/fclib), FCLIB_REPEAT (5),
# PREFIX_STEPS (50), FULL_STEPS (the problems' own), ROBUST_THETAS, ROBUST_ARC_FLAT (100),
# ROBUST_ARC_CURVED (50), ROBUST_PROBLEMS (arch-flat arch-curved), SKIP_SETUP=1 to use an existing build without running setup.sh.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
out="${RESULTS_DIR:-$here/results}/compare"
robust_out="${RESULTS_DIR:-$here/results}/robustness"
read -r -a robust_thetas <<< "${ROBUST_THETAS:-0.1 0.2 0.5 1.0}"
declare -A robust_arc=([arch-flat]="${ROBUST_ARC_FLAT:-100}" [arch-curved]="${ROBUST_ARC_CURVED:-50}")
time_limit="${TIME_LIMIT:-5}"
block_repeat="${BLOCK_REPEAT:-5}"
prefix_steps="${PREFIX_STEPS:-50}"
# FULL_STEPS: a documented prefix of the full paths instead (empty: each problem's own steps).
full_steps=(); [[ -n "${FULL_STEPS:-}" ]] && full_steps=(--steps "$FULL_STEPS")
if [[ "${SKIP_SETUP:-0}" != 1 ]]; then "$here/scripts/setup.sh" "$build" || exit 1; fi
cb="$build/bin/contactbench"

# The formulations this build has (`contactbench list` marks the others "(not built)").
# The distributed dist-* formulations are left out: on one process they are the methods of their
# serial counterparts through PETSc's SNES (docs/scale-out.md), and compare runs one process.
mapfile -t available < <("$cb" list | awk '/^formulations:/ {f = 1; next} /^[a-z]/ {f = 0}
  f && NF && $0 !~ /\(not built\)/ && $1 !~ /^dist-/ {print $1}')
join() { local IFS=,; echo "$*"; }
all="$(join "${available[@]}")"
# The full paths without the two NLopt formulations that take seconds per step (see above).
full_path_set="$(join $(printf '%s\n' "${available[@]}" | grep -vx -e nlopt-mpcc -e nlopt-merit))"

status=0
compare() {  # compare DIR ARGS...
  local dir="$1"; shift
  rm -rf "$dir"  # one comparison per directory: the CSVs are appended to, never mixed
  echo "== contactbench compare $* --out $dir" >&2
  local start=$SECONDS
  "$cb" compare "$@" --time-limit "$time_limit" --out "$dir"
  local rc=$?
  echo "   $((SECONDS - start)) s (exit status $rc)" >&2
  ((rc == 0)) || status=3
}

sets=("$@")
((${#sets[@]})) || sets=(arch-flat arch-curved arch-flat-prefix arch-curved-prefix block robustness)
for set in "${sets[@]}"; do
  case "$set" in
    arch-flat|arch-curved)
      compare "$out/$set" --problem "$set" --formulations "$full_path_set" --starts warm,cold \
          "${full_steps[@]}" ;;
    arch-flat-prefix|arch-curved-prefix)
      compare "$out/$set" --problem "${set%-prefix}" --formulations "$all" --starts warm,cold \
          --steps "$prefix_steps" ;;
    block)
      compare "$out/block" --problem block --formulations "$all" --starts cold \
          --repeat "$block_repeat" ;;
    fclib)
      compare "$out/fclib" --problem-dir "${FCLIB_DIR:-$here/tests/data/fclib}" \
          --set friction=ignore --formulations "$all" --repeat "${FCLIB_REPEAT:-5}" ;;
    robustness)
      for problem in ${ROBUST_PROBLEMS:-arch-flat arch-curved}; do
        for theta in "${robust_thetas[@]}"; do
          steps=$(awk -v a="${robust_arc[$problem]}" -v t="$theta" 'BEGIN {printf "%d", a / t + 0.5}')
          compare "$robust_out/$problem/theta-$theta" --problem "$problem" \
              --formulations "$full_path_set" --starts warm --arc-length "$theta" --steps "$steps"
        done
      done ;;
    *) echo "run_compare: unknown set '$set'" >&2; exit 2 ;;
  esac
done
exit $status
