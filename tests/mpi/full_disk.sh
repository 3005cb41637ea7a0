#!/bin/sh
# A record write that fails on process 0 of a distributed run (a full disk; here a file size
# limit of a few KiB, set in each process alone so that mpirun's own files are not limited)
# must end every process with exit 3, run.json written with the write's failure, and never
# hang (issue 30; bench/harness/process_agreement.h, docs/hardening.md). Each distributed
# formulation is tried: a hang is ended by `timeout` and fails the test.
# Usage: full_disk.sh CONTACTBENCH MPIEXEC WORK_DIR
set -u
bin=$1 mpiexec=$2 work=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work" || exit 1

for formulation in dist-implicit-fb dist-nonsmooth-fb dist-active-set dist-petsc-rsls; do
  out="$work/$formulation"
  # Each process reports its own status on a line of its own; 16 KiB holds the first records
  # and run.json, not the iterations of the path.
  export OUT="$out"
  timeout -s KILL 300 "$mpiexec" -n 2 -x OUT /bin/sh -c 'ulimit -f 16; "$0" "$@" 2>"$OUT.err.$OMPI_COMM_WORLD_RANK"; echo "process $OMPI_COMM_WORLD_RANK exit $?"' \
    "$bin" run --problem arch-curved --formulation "$formulation" --out "$out" \
    >"$out.log" 2>&1 </dev/null
  [ $? -eq 137 ] && { echo "$formulation: hung (killed after 300 s)"; exit 1; }
  for rank in 0 1; do
    grep -q "process $rank exit 3" "$out.log" ||
      { echo "$formulation: process $rank did not exit 3:"; cat "$out.log" "$out.err.$rank"; exit 1; }
  done
  grep -q "cannot write" "$out.err.0" || { echo "$formulation: process 0 did not say why"; exit 1; }
  python3 -c 'import json, sys; r = json.load(open(sys.argv[1] + "/run.json"))
sys.exit(0 if r["exit_status"] == 3 and "cannot write" in r["reason"] else "run.json: %s %s"
         % (r["exit_status"], r["reason"]))' "$out" || exit 1
  echo "$formulation: a full disk on process 0 ends both processes with exit 3"
done
exit 0
