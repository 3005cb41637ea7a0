#!/bin/sh
# Two processes against one (docs/scale-out.md): P1 (block, n = 8), the first steps of P2
# (arch-flat) and P3 (arch-curved), and hertz-3d on a 6^3 mesh run serially with implicit-fb and
# with mpirun -n 2 with the distributed formulations; the answers must agree
# (scripts/compare_answers.py). dist_options are the distributed run's own (the iterative linear
# solve, linear=amg).
# Usage: two_processes.sh CONTACTBENCH MPIEXEC SOURCE_DIR WORK_DIR
set -u
bin=$1 mpiexec=$2 source=$3 work=$4
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work" || exit 1

# run LABEL MPI_PREFIX... -- contactbench arguments
check() {
  label=$1 problem=$2 formulation=$3
  shift 3
  "$bin" run --problem "$problem" --formulation implicit-fb --out "$work/$label-serial" "$@" \
    2>"$work/$label-serial.log" || { cat "$work/$label-serial.log"; exit 1; }
  "$mpiexec" -n 2 "$bin" run --problem "$problem" --formulation "$formulation" \
    --out "$work/$label-dist" "$@" $dist_options >"$work/$label-dist.log" 2>&1
  status=$?
  if [ $status -ne 0 ]; then cat "$work/$label-dist.log"; exit 1; fi
  echo "$label: $formulation on 2 processes against implicit-fb"
  # run.json records the process count (docs/scale-out.md).
  python3 -c 'import json, sys; n = [json.load(open(d + "/run.json"))["processes"]
for d in sys.argv[1:]]; sys.exit(0 if n == [1, 2] else "run.json processes: %s, not [1, 2]" % n)' \
    "$work/$label-serial" "$work/$label-dist" || exit 1
  python3 "$source/scripts/compare_answers.py" "$work/$label-serial" "$work/$label-dist" || exit 1
}

# One process under the launcher is a plain run (it used to exit 1 after writing verified
# records: the stand-in MPI took the finalisation): status 0 and the same answers.
one_process() {
  label=$1 problem=$2 formulation=$3
  shift 3
  "$bin" run --problem "$problem" --formulation "$formulation" --out "$work/$label-plain" "$@" \
    2>"$work/$label-plain.log" || { cat "$work/$label-plain.log"; exit 1; }
  "$mpiexec" -n 1 "$bin" run --problem "$problem" --formulation "$formulation" \
    --out "$work/$label-mpirun" "$@" >"$work/$label-mpirun.log" 2>&1 ||
    { echo "$label: mpirun -n 1 failed"; cat "$work/$label-mpirun.log"; exit 1; }
  echo "$label: $formulation under mpirun -n 1 against a plain run"
  python3 "$source/scripts/compare_answers.py" "$work/$label-plain" "$work/$label-mpirun" || exit 1
}
one_process p2-one arch-flat dist-implicit-fb --steps 6
one_process p1-one block implicit-fb --set n=8

dist_options=""
check p1 block dist-implicit-fb --set n=8
check p1-rsls block dist-petsc-rsls --set n=8
check p2 arch-flat dist-implicit-fb --steps 6
check p3 arch-curved dist-active-set --steps 6
check p4 hertz-3d dist-implicit-fb --set n=6 --set nz=6
dist_options="--option linear=amg"
check p1-amg block dist-active-set --set n=16
exit 0
