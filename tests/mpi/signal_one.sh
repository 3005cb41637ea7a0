#!/bin/sh
# A signal to one process of a distributed run (SIGTERM to process 1, then to process 0, in the
# middle of the path) ends the run with run.json's counts matching the records: attempts the
# rows of steps.csv, accepted steps its accepted rows. Before, run.json said 0 and 0 beside
# 66-92 rows (issue 30). The run must also end (a hang is killed by `timeout` and fails).
# Usage: signal_one.sh CONTACTBENCH MPIEXEC WORK_DIR
set -u
bin=$1 mpiexec=$2 work=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work" || exit 1
export PIDS="$work/pid"

for rank in 1 0; do
  out="$work/rank$rank"
  rm -f "$PIDS".*
  timeout -s KILL 300 "$mpiexec" -n 2 -x PIDS /bin/sh -c 'echo $$ >"$PIDS.$OMPI_COMM_WORLD_RANK"; exec "$0" "$@"' \
    "$bin" run --problem arch-curved --formulation dist-implicit-fb --steps 100000 --out "$out" \
    >"$out.log" 2>&1 </dev/null &
  job=$!
  # Some steps in (the header and 20 rows), then the signal to one process.
  i=0
  while [ "$(cat "$out/steps.csv" 2>/dev/null | wc -l)" -lt 21 ]; do
    i=$((i + 1))
    [ $i -gt 1200 ] && { echo "rank $rank: no 20 steps in 120 s"; cat "$out.log"; exit 1; }
    sleep 0.1
  done
  kill -TERM "$(cat "$PIDS.$rank")"
  wait $job
  status=$?
  [ $status -eq 137 ] && { echo "SIGTERM to process $rank: hung (killed after 300 s)"; exit 1; }
  python3 - "$out" "$rank" <<'PY' || { cat "$out.log"; exit 1; }
import csv, json, sys
out, rank = sys.argv[1], sys.argv[2]
run = json.load(open(out + "/run.json"))
rows = list(csv.DictReader(open(out + "/steps.csv", newline="")))
accepted = sum(r["accepted"] == "true" for r in rows)
counts = run["counts"]
print("SIGTERM to process %s: exit %s (%s); %d rows, %d accepted; run.json %d attempts, %d "
      "accepted" % (rank, run["exit_status"], run["reason"], len(rows), accepted,
                    counts["attempts"], counts["accepted_steps"]))
sys.exit(0 if counts["attempts"] == len(rows) and counts["accepted_steps"] == accepted
         and len(rows) >= 20 else "run.json's counts do not match steps.csv")
PY
done
exit 0
