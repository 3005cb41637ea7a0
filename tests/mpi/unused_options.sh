#!/bin/sh
# --petsc-options that PETSc never reads stop a distributed run after its first solve, on every
# process, naming them, as they stop the petsc-* formulations (formulations/petsc/
# petsc_unused_options.h); options PETSc reads run as before (issue 30).
# Usage: unused_options.sh CONTACTBENCH MPIEXEC WORK_DIR
set -u
bin=$1 mpiexec=$2 work=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work" || exit 1

# run FORMULATION OPTIONS: both processes' statuses in $work/log, process N's stderr in
# $work/err.N.
export ERR="$work/err"
run() {
  rm -rf "$work/out"
  timeout -s KILL 300 "$mpiexec" -n 2 -x ERR /bin/sh -c '"$0" "$@" 2>"$ERR.$OMPI_COMM_WORLD_RANK"; echo "process $OMPI_COMM_WORLD_RANK exit $?"' \
    "$bin" run --problem arch-curved --formulation "$1" --steps 3 --petsc-options "$2" \
    --out "$work/out" >"$work/log" 2>&1 </dev/null
  [ $? -eq 137 ] && { echo "$1 '$2': hung (killed after 300 s)"; exit 1; }
}

for formulation in dist-implicit-fb dist-active-set; do
  for option in -snes_monitr -log_view; do
    run "$formulation" "-snes_max_it 40 $option"
    for rank in 0 1; do
      grep -q "process $rank exit 3" "$work/log" ||
        { echo "$formulation $option: process $rank did not exit 3:"; cat "$work/log"; exit 1; }
    done
    grep -q "PETSc did not use $option" "$work/err.0" ||
      { echo "$formulation $option: not named:"; cat "$work/err.0"; exit 1; }
    echo "$formulation $option: refused on both processes"
  done
  run "$formulation" "-snes_max_it 40"
  for rank in 0 1; do
    grep -q "process $rank exit 0" "$work/log" ||
      { echo "$formulation -snes_max_it 40: process $rank did not exit 0:"; cat "$work/log" "$work/err.0"; exit 1; }
  done
  echo "$formulation -snes_max_it 40: runs"
done
exit 0
