#!/usr/bin/env bash
# Invariance under rounding (issue 25, section 2): runs the report's examples and a selection of
# the readings under perturbations that must not change them, then compares what must be
# invariant against the baseline (one BLAS thread, `--linear-solver cholmod`) with
# scripts/invariance.py, which prints a markdown table (one row per example x perturbation) and
# ends with 'invariance: N passed, N failed'. Exit status 1 when any invariant differs, 2 on a
# usage error.
#
# The examples, as scripts/run_suite.sh runs them: P1 `block` cold, eta cases 1-4, Newton and
# dogleg, and eta case 3 near the solution; P2 `arch-flat` with the branch switch and P3
# `arch-curved`, Newton and quasi-Newton. The readings, as scripts/run_readings.sh runs them
# (P2 Newton and quasi-Newton, P3 quasi-Newton): howe, centre-thinned, x-braced, from-centre and
# howe-vertical, the ones whose limit points, bifurcation points or stopping step
# docs/findings.md quotes.
# The perturbations: OPENBLAS_NUM_THREADS=2, and `--linear-solver klu`, `umfpack`, `sparse-lu`
# (each with one BLAS thread). A build at -O2 against -O3 -march=native is not offered.
#
# Every record goes under OUT_DIR (OUT_DIR/<perturbation>/<example>/, each run's standard error
# and exit status beside its directory; OUT_DIR/plan.csv lists the runs), about 200 MB; never
# into results/. An OUT_DIR that holds other files is refused; an earlier check's is replaced.
# The run time, measured on the 2-core VM of results/README.md, is in docs/findings.md
# ("Invariance under rounding").
#
# Usage: scripts/check_invariance.sh [CONTACTBENCH_BINARY] OUT_DIR
#   CONTACTBENCH_BINARY  default build/bin/contactbench
# Environment: JOBS runs at once (default 2); SKIP_SPARSE_LU=1 leaves the slowest linear solver
# out; READINGS="howe x-braced ..." another selection of the readings ("" for none, "all" for
# the eleven of run_readings.sh).
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage="usage: scripts/check_invariance.sh [CONTACTBENCH_BINARY] OUT_DIR"
case $# in
  1) cb="$here/build/bin/contactbench"; out="$1" ;;
  2) cb="$1"; out="$2" ;;
  *) echo "$usage" >&2; exit 2 ;;
esac
if [[ ! -x $cb ]]; then
  echo "check_invariance: no contactbench at $cb ($usage)" >&2
  exit 2
fi
case "$(realpath -m "$out")/" in
  "$(realpath -m "$here/results")"/*)
    echo "check_invariance: OUT_DIR must not be in results/ (the committed run)" >&2
    exit 2 ;;
esac
if [[ -e $out && ! -f $out/plan.csv && -n "$(ls -A "$out" 2>/dev/null)" ]]; then
  echo "check_invariance: $out holds files of something else; give a new or empty OUT_DIR" \
       "(an earlier check's OUT_DIR, with its plan.csv, is replaced)" >&2
  exit 2
fi
jobs="${JOBS:-2}"

# example | kind (fixed: one solve, its answer compared; path) | contactbench run arguments
examples=()
for solver in newton dogleg; do
  for eta in 1 2 3 4; do
    examples+=("p1/eta$eta-$solver|fixed|--problem block --formulation implicit-fb --start cold
      --solver $solver --eta $eta")
  done
  examples+=("p1/eta3-near-$solver|fixed|--problem block --formulation implicit-fb --start near
    --solver $solver --eta 3")
done
for solver in newton quasi-newton; do
  examples+=("p2/$solver|path|--problem arch-flat --formulation implicit-fb --solver $solver
    --bifurcations switch --save-every 100")
  examples+=("p3/$solver|path|--problem arch-curved --formulation implicit-fb --solver $solver
    --save-every 200")
done
# The readings of scripts/run_readings.sh: name | P2 settings | P3 settings.
mapfile -t all_readings < <(grep -v -e '^#' -e '^$' "$here/scripts/readings.txt")
chosen="${READINGS-howe centre-thinned x-braced from-centre howe-vertical}"
for entry in "${all_readings[@]}"; do
  IFS='|' read -r reading p2 p3 <<<"$entry"
  if [[ $chosen != all && " $chosen " != *" $reading "* ]]; then continue; fi
  sets2="" sets3=""
  for s in $p2; do sets2+=" --set $s"; done
  for s in $p3; do sets3+=" --set $s"; done
  examples+=("readings/$reading/arch-flat|path|--problem arch-flat --formulation implicit-fb$sets2
    --solver newton")
  examples+=("readings/$reading/arch-flat-qn|path|--problem arch-flat --formulation implicit-fb$sets2
    --solver quasi-newton")
  examples+=("readings/$reading/arch-curved|path|--problem arch-curved --formulation implicit-fb$sets3
    --solver quasi-newton")
done

# perturbation | OPENBLAS_NUM_THREADS | linear solver; the first is the baseline.
perturbations=("baseline|1|cholmod" "threads-2|2|cholmod" "klu|1|klu" "umfpack|1|umfpack")
[[ "${SKIP_SPARSE_LU:-0}" != 1 ]] && perturbations+=("sparse-lu|1|sparse-lu")

rm -rf "$out"
mkdir -p "$out"
plan="$out/plan.csv"
echo "example,kind,perturbation,threads,linear_solver,dir" >"$plan"

start=$SECONDS
running=0
launch() {  # launch DIR THREADS ARGS...: one run in the background; DIR.status: exit status,
            # start and end time
  local dir="$1" threads="$2"; shift 2
  mkdir -p "$(dirname "$dir")"
  (
    t0=$EPOCHREALTIME
    OPENBLAS_NUM_THREADS="$threads" "$cb" run "$@" --out "$dir" >/dev/null 2>"$dir.log"
    rc=$?
    echo "$rc $t0 $EPOCHREALTIME" >"$dir.status"
  ) &
  running=$((running + 1))
  if ((running >= jobs)); then wait -n; running=$((running - 1)); fi
}
runs=0
for p in "${perturbations[@]}"; do
  IFS='|' read -r pert threads solver <<<"$p"
  for e in "${examples[@]}"; do
    IFS='|' read -r name kind spec <<<"${e//$'\n'/ }"
    read -ra args <<<"$spec"
    echo "$name,$kind,$pert,$threads,$solver,$pert/$name" >>"$plan"
    launch "$out/$pert/$name" "$threads" "${args[@]}" --linear-solver "$solver"
    runs=$((runs + 1))
  done
done
wait
echo "check_invariance: $runs runs in $((SECONDS - start)) s (JOBS=$jobs), records in $out" >&2
/usr/bin/python3 "$here/scripts/invariance.py" "$out"
