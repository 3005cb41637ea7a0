#!/bin/sh
# A refused --out (records of an earlier run, the root directory) ends every process of a
# distributed run with status 2, as process 0 does: the others take process 0's word for the
# status (bench/harness/process_agreement.h). Before, they ended with 3, and mpirun's status
# was whichever process ended first (issue 30).
# Usage: refused_out.sh CONTACTBENCH MPIEXEC WORK_DIR
set -u
bin=$1 mpiexec=$2 work=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work/earlier" || exit 1
: >"$work/earlier/steps.csv"

for out in "$work/earlier" /; do
  timeout -s KILL 120 "$mpiexec" -n 2 /bin/sh -c '"$0" "$@" 2>/dev/null; echo "process $OMPI_COMM_WORLD_RANK exit $?"' \
    "$bin" run --problem arch-curved --formulation dist-implicit-fb --out "$out" \
    >"$work/log" 2>&1 </dev/null
  for rank in 0 1; do
    grep -q "process $rank exit 2" "$work/log" ||
      { echo "--out $out: process $rank did not exit 2:"; cat "$work/log"; exit 1; }
  done
  echo "--out $out: refused with status 2 on both processes"
done
[ -e "$work/earlier/run.json" ] && { echo "a refused run wrote run.json"; exit 1; }
exit 0
