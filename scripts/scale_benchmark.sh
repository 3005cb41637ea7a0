#!/bin/sh
# The distributed scale benchmark (docs/scale-out.md): P1 (block) at the given n, on 1 and 2
# processes, with the direct solve (MUMPS, the default) and the iterative one (AMG, below), one
# fixed-load solve each, cold start. Appends one CSV row per run to OUT: n, d, processes,
# linear solve, formulation, verified, Newton iterations, solve time (steps.csv's time_s), wall
# time of the whole command, the largest peak resident memory of a process (GNU time's %M) and
# the linear iterations (steps.csv's linear_solves: one per Newton iteration with the direct
# solve, the Krylov iterations summed over Newton with AMG).
# Usage: scripts/scale_benchmark.sh CONTACTBENCH OUT.csv FORMULATION "N..." "PROCESSES..." "SOLVES..."
#   e.g. scripts/scale_benchmark.sh build-mpi/bin/contactbench results/scale/p1.csv \
#          dist-active-set "100 200 400" "1 2" "direct amg"
set -u
bin=$1 out=$2 formulation=$3 sizes=$4 processes=$5 solves=$6
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
[ -s "$out" ] || echo "n,d,processes,linear_solve,formulation,verified,iterations,solve_s,wall_s,max_rss_mb_per_process,linear_iterations" >"$out"
for n in $sizes; do
  for np in $processes; do
    for solve in $solves; do
      case $solve in
        direct) options="" ;;
        amg) options="--option linear=amg" ;;
        *) echo "unknown solve $solve"; exit 2 ;;
      esac
      dir=$work/$n-$np-$solve
      start=$(date +%s.%N)
      mpirun -n "$np" /usr/bin/time -f "max_rss_kb %M" "$bin" run --problem block --set n="$n" \
        --formulation "$formulation" --start cold --out "$dir" --allow-memory \
        $options >"$dir.log" 2>&1
      end=$(date +%s.%N)
      rss=$(grep -o "max_rss_kb [0-9]*" "$dir.log" | awk '{ if ($2 > m) m = $2 } END { printf "%.0f", m / 1024 }')
      row=$(python3 - "$dir/steps.csv" <<'PY'
import csv, sys
try:
    r = [x for x in csv.DictReader(open(sys.argv[1]))][-1]
    print(f"{r['verified']},{r['iterations']},{r['time_s']},{r['linear_solves']}")
except Exception:
    print("false,,,")
PY
)
      d=$(awk -v n="$n" 'BEGIN { printf "%d", 2 * (n + 1) * (n + 1) }')
      linear=${row##*,} row=${row%,*}
      echo "$n,$d,$np,$solve,$formulation,$row,$(echo "$end - $start" | bc),$rss,$linear" | tee -a "$out"
    done
  done
done
rm -rf "$work"
