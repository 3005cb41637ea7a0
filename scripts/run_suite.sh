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
# and last, the invariance check (scripts/check_invariance.sh, about two minutes): the examples
# and readings again under other BLAS thread counts and linear solvers, compared with the first
# run; its table goes to standard output, its records (about 200 MB) to a temporary directory
# that is removed afterwards (or to INVARIANCE_DIR, kept), none to RESULTS_DIR: the reports do
# not read them. docs/findings.md ("Invariance under rounding") has its table.
# A run that fails keeps its records and the job goes on; the reports say what failed. A failed
# invariance check (an invariant that moved) makes the job's exit status 3 too.
# Usage: scripts/run_suite.sh [--quick]
# Environment:
#   BUILD_DIR=DIR    the build to set up and run (default build/)
#   RESULTS_DIR=DIR  where the records, figures and reports go (default results/, the committed
#                    run: give another directory to keep it as it is; with --quick,
#                    results-quick/)
#   SKIP_SETUP=1     neither install nor build: run the contactbench already built in BUILD_DIR
#   SKIP_READINGS=1, SKIP_SOLID3D=1, SKIP_COMPARE=1, SKIP_BENCH=1 leave those parts (and their
#                    old files) alone; SKIP_INVARIANCE=1 leaves the invariance check out
#   INVARIANCE_DIR=DIR  keep the invariance check's records in DIR (not inside RESULTS_DIR)
#   QUICK=1          the same as --quick
#
# --quick, the quick mode: a first look and a check of the pipeline in a minute or two after
# the build (results/README.md has the time measured), not results to quote. The report's
# examples, the readings and the 3-D solids run whole (seconds each), so REPORT.md is the full
# one; the comparison runs only the sets arch-flat and arch-curved, on the first FULL_STEPS
# (default 100) steps of each path, and block; the prefix and step-size sets and the benchmarks
# are left out (SKIP_BENCH=0 adds the benchmarks, whole, at their full cost), and so is the
# invariance check (SKIP_INVARIANCE=0 adds it, whole).
# It writes RESULTS_DIR/QUICK_MODE.txt, which says what was shortened, and REPORT.md and
# COMPARISON.md open with a line saying they are the quick mode's (results/plotlib/quick.py).
# It refuses to write into results/, the committed run.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick="${QUICK:-0}"
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    *) echo "run_suite: unknown argument '$arg' (usage: scripts/run_suite.sh [--quick])" >&2
       exit 2 ;;
  esac
done
build="${BUILD_DIR:-$here/build}"
skip_bench="${SKIP_BENCH:-0}"
skip_invariance="${SKIP_INVARIANCE:-0}"
if [[ $quick == 1 ]]; then
  out="${RESULTS_DIR:-$here/results-quick}"
  skip_bench="${SKIP_BENCH:-1}"
  skip_invariance="${SKIP_INVARIANCE:-1}"
  quick_steps="${FULL_STEPS:-100}"
  if [[ "$(realpath -m "$out")" == "$(realpath -m "$here/results")" ]]; then
    echo "run_suite: --quick would mix shortened records into results/, the committed run;" \
         "give another RESULTS_DIR (default results-quick/)" >&2
    exit 2
  fi
else
  out="${RESULTS_DIR:-$here/results}"
fi
if [[ "${SKIP_SETUP:-0}" != 1 ]]; then "$here/scripts/setup.sh" "$build" || exit 1; fi
cb="$build/bin/contactbench"
if [[ ! -x $cb ]]; then
  echo "run_suite: no $cb (SKIP_SETUP=1 needs a build in BUILD_DIR)" >&2
  exit 1
fi
mkdir -p "$out"

# The quick mode's marker, with what it shortened: results/plot.py reads it. A full run into the
# same directory removes it.
marker="$out/QUICK_MODE.txt"
rm -f "$marker"
if [[ $quick == 1 ]]; then
  {
    whole="the report's examples"
    [[ "${SKIP_READINGS:-0}" != 1 ]] && whole+=", the readings"
    [[ "${SKIP_SOLID3D:-0}" != 1 ]] && whole+=", the 3-D solids"
    echo "Run whole: $whole."
    [[ "${SKIP_COMPARE:-0}" != 1 ]] &&
      echo "The comparison sets arch-flat and arch-curved on the first $quick_steps steps of" \
           "each path, block whole; no prefix or step-size sets."
    [[ $skip_bench != 1 ]] && echo "The benchmarks whole."
    [[ $skip_bench == 1 ]] && echo "No benchmarks."
    [[ $skip_invariance != 1 ]] && echo "The invariance check whole (its table in the log only)."
    for name in READINGS SOLID3D COMPARE; do
      skip="SKIP_$name"
      [[ "${!skip:-0}" == 1 ]] && echo "$skip=1: that part's records, if any, are an earlier run's."
    done
  } >"$marker"
fi

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

# The parts' own scripts, with the set-up done; whole (not their own QUICK=1 forms).
part() { SKIP_SETUP=1 BUILD_DIR="$build" RESULTS_DIR="$out" QUICK=0 "$@" || status=3; }
if [[ "${SKIP_READINGS:-0}" != 1 ]]; then part "$here/scripts/run_readings.sh"; fi
if [[ "${SKIP_SOLID3D:-0}" != 1 ]]; then part "$here/scripts/run_solid3d.sh"; fi
if [[ "${SKIP_COMPARE:-0}" != 1 ]]; then
  if [[ $quick == 1 ]]; then
    FULL_STEPS="$quick_steps" part "$here/scripts/run_compare.sh" arch-flat arch-curved block
  else
    part "$here/scripts/run_compare.sh"
  fi
fi
if [[ $skip_bench != 1 ]]; then part "$here/scripts/run_bench.sh"; fi

/usr/bin/python3 "$here/results/plot.py" "$out" || status=3

# The invariance check, last: its table to standard output, its records outside RESULTS_DIR.
if [[ $skip_invariance != 1 ]]; then
  if [[ -n "${INVARIANCE_DIR:-}" ]]; then
    inv_dir="$INVARIANCE_DIR"
  else
    inv_dir="$(mktemp -d "${TMPDIR:-/tmp}/contactbench-invariance.XXXXXX")"
  fi
  case "$(realpath -m "$inv_dir")/" in
    "$(realpath -m "$out")"/*)
      echo "run_suite: INVARIANCE_DIR must not be inside RESULTS_DIR" >&2
      status=3 ;;
    *)
      echo "== scripts/check_invariance.sh $cb $inv_dir" >&2
      "$here/scripts/check_invariance.sh" "$cb" "$inv_dir" || status=3
      if [[ -z "${INVARIANCE_DIR:-}" ]]; then rm -rf "$inv_dir"; fi ;;
  esac
fi
exit $status
