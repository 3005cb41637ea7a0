#!/usr/bin/env bash
# The reproduction check (docs/findings.md, "Reproduction check"): reruns what the committed
# records of REPORT.md came from, as the main job runs them (scripts/run_suite.sh: the report's
# examples P1 `block`, P2 `arch-flat`, P3 `arch-curved`; scripts/run_readings.sh, the readings;
# scripts/run_solid3d.sh, the 3-D solids), into a temporary directory, about a minute, and compares each run with the committed one by
# `scripts/diff_records.py --invariants`: the exit status, the accepted steps, the kinks, limit and
# bifurcation points and the branches exactly (their lambdas and P1's answers to 1e-6), the
# iteration histograms within a stated tolerance, the timings not at all. A change that moves a
# committed result fails it until the records are regenerated (--update) and the commit says
# what moved and why. The comparison sets and the benchmarks (COMPARISON.md) are not rerun
# (about 100 minutes): docs/findings.md says how they are covered.
#
# Usage: scripts/check_results.sh [--update | --comparison]
#   --update      rerun into results/ itself: the examples', the readings' and the 3-D solids'
#                 records are replaced and results/REPORT.md, COMPARISON.md and the figures
#                 regenerated (results/plot.py); the comparison with the records they replace
#                 is printed as without it. Then commit them, saying what moved and why.
#   --comparison  instead, the summary check of the comparison sets: replay the first
#                 FULL_STEPS (default 100) steps of the sets arch-flat and arch-curved and the
#                 whole of block and of the FCLIB problem set fclib (one repetition each;
#                 scripts/run_compare.sh, about a minute) and compare with the committed sets
#                 over the same steps by scripts/diff_comparison.py: per formulation x start
#                 the verified steps and the median iterations, as COMPARISON.md aggregates
#                 them, and per FCLIB problem x formulation x start the status and iterations
#                 (time-limited solves aside). The prefix and step-size sets and the benchmarks
#                 are not replayed.
# Environment: BUILD_DIR (default build/: the contactbench built there is run, nothing is built),
# FULL_STEPS (--comparison: the steps replayed, default 100),
# KEEP_DIR=DIR keeps the rerun's records in DIR (new or empty, not inside results/) instead of a
# temporary directory that is removed afterwards. Nothing else is written (with --update,
# results/). Exit status 1 when a run differs (0 with --update), 2 on a usage error.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
update=0 comparison=0
usage="usage: scripts/check_results.sh [--update | --comparison]"
for arg in "$@"; do
  case "$arg" in
    --update) update=1 ;;
    --comparison) comparison=1 ;;
    *) echo "check_results: unknown argument '$arg' ($usage)" >&2; exit 2 ;;
  esac
done
if ((update && comparison)); then echo "check_results: $usage" >&2; exit 2; fi
build="${BUILD_DIR:-$here/build}"
if [[ ! -x $build/bin/contactbench ]]; then
  echo "check_results: no $build/bin/contactbench (build first, or give BUILD_DIR)" >&2
  exit 2
fi
if [[ -n "${KEEP_DIR:-}" ]]; then
  tmp="$KEEP_DIR"
  case "$(realpath -m "$tmp")/" in
    "$(realpath -m "$here/results")"/*)
      echo "check_results: KEEP_DIR must not be inside results/" >&2; exit 2 ;;
  esac
  if [[ -n "$(ls -A "$tmp" 2>/dev/null)" ]]; then
    echo "check_results: KEEP_DIR $tmp is not empty" >&2; exit 2
  fi
  mkdir -p "$tmp"
else
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/contactbench-check-results.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
fi

start=$SECONDS
if ((comparison)); then
  SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$tmp/results" FULL_STEPS="${FULL_STEPS:-100}" \
    FCLIB_REPEAT=1 "$here/scripts/run_compare.sh" arch-flat arch-curved block fclib >"$tmp/log.txt" 2>&1
  echo "check_results: replayed arch-flat and arch-curved (${FULL_STEPS:-100} steps), block and fclib" \
       "in $((SECONDS - start)) s (log: $tmp/log.txt)" >&2
  /usr/bin/python3 "$here/scripts/diff_comparison.py" "$here/results" "$tmp/results"
  status=$?
  if ((status == 1)); then
    echo "check_results: FAILED: the code no longer gives the committed comparison sets" \
         "(above); regenerate them (scripts/run_compare.sh, about an hour) and say in the" \
         "commit what moved and why" >&2
  fi
  exit $status
fi
# The main job itself, without the comparison sets, the benchmarks and the invariance check: one
# list of commands. Into the temporary directory; with --update into results/ itself (so that
# the records name it, as the main job's do), the committed records copied aside first.
parts=(block arch-flat arch-curved readings solid3d)
committed="$here/results" records="$tmp/results"
if ((update)); then
  committed="$tmp/committed" records="$here/results"
  mkdir -p "$committed"
  for part in "${parts[@]}"; do
    if [[ -e $records/$part ]]; then cp -r "$records/$part" "$committed/$part"; fi
  done
fi
SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$records" SKIP_READINGS=0 SKIP_SOLID3D=0 \
  SKIP_COMPARE=1 SKIP_BENCH=1 SKIP_INVARIANCE=1 QUICK=0 KEEP_FULL=0 \
  "$here/scripts/run_suite.sh" >"$tmp/log.txt" 2>&1
echo "check_results: reran ${parts[*]} in $((SECONDS - start)) s (log: $tmp/log.txt)" >&2

status=0
for part in "${parts[@]}"; do
  echo "== $part: the committed records against the rerun" >&2
  /usr/bin/python3 "$here/scripts/diff_records.py" --invariants "$committed/$part" \
    "$records/$part" || status=1
done

if ((update)); then
  # run_suite.sh has regenerated REPORT.md, COMPARISON.md and the figures from them.
  echo "check_results: results/ regenerated (what moved: above); commit it, saying what moved" \
       "and why" >&2
  exit 0
fi
if ((status != 0)); then
  echo "check_results: FAILED: the code no longer gives the committed records (above); if the" \
       "change is meant, regenerate them (scripts/check_results.sh --update) and say in the" \
       "commit what moved and why" >&2
fi
echo "check_results: $((SECONDS - start)) s in all" >&2
exit $status
