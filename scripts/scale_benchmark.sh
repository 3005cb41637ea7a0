#!/bin/sh
# The distributed scale benchmark (docs/scale-out.md): PROBLEM at the given sizes, on the given
# numbers of processes, with the direct solve (MUMPS, the default) and the iterative one (AMG,
# below), one fixed-load solve each, cold start. Appends one CSV row per run to OUT: n, d,
# processes, linear solve, formulation, verified, Newton iterations, solve time (steps.csv's
# time_s), wall time of the whole command, the largest peak resident memory of a process (GNU
# time's %M), the linear iterations (steps.csv's linear_solves: one per Newton iteration with the
# direct solve, the Krylov iterations summed over Newton with AMG), the problem and the 1-minute
# load average before the run (a time is only comparable with others taken at the same load).
# PROBLEM: block (P1, n x n elements; the default) or hertz-3d (n = nz, uniform cells:
# grading = 1); d is the free displacement dofs.
# Usage: scripts/scale_benchmark.sh CONTACTBENCH OUT.csv FORMULATION "N..." "PROCESSES..." "SOLVES..." [PROBLEM]
#   e.g. scripts/scale_benchmark.sh build-mpi/bin/contactbench results/scale/p1.csv \
#          dist-active-set "100 200 400" "1 2" "direct amg"
set -u
bin=$1 out=$2 formulation=$3 sizes=$4 processes=$5 solves=$6 problem=${7:-block}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
case $problem in
  block | hertz-3d) ;;
  *) echo "scale_benchmark: unknown PROBLEM '$problem' (block or hertz-3d)" >&2; exit 2 ;;
esac
work=$(mktemp -d)
header="n,d,processes,linear_solve,formulation,verified,iterations,solve_s,wall_s,max_rss_mb_per_process,linear_iterations,problem,load_1min"
if [ ! -s "$out" ]; then
  echo "$header" >"$out"
elif [ "$(head -n 1 "$out")" != "$header" ]; then
  echo "scale_benchmark: $out has other columns (an older benchmark's); give a new file" >&2
  exit 2
fi
for n in $sizes; do
  case $problem in
    block)
      settings="--set n=$n"
      d=$(awk -v n="$n" 'BEGIN { printf "%d", 2 * (n + 1) * (n + 1) }') ;;
    hertz-3d)  # 3 (n+1)^3 less u_x on x = 0 and u_y on y = 0
      settings="--set n=$n --set nz=$n --set grading=1"
      d=$(awk -v n="$n" 'BEGIN { printf "%d", 3 * (n + 1) ^ 3 - 2 * (n + 1) ^ 2 }') ;;
  esac
  for np in $processes; do
    for solve in $solves; do
      case $solve in
        direct) options="" ;;
        amg) options="--option linear=amg" ;;
        *) echo "scale_benchmark: unknown solve '$solve' (direct or amg)" >&2; exit 2 ;;
      esac
      dir=$work/$n-$np-$solve
      load=$(cut -d' ' -f1 /proc/loadavg)
      start=$(date +%s.%N)
      # shellcheck disable=SC2086 # settings and options are lists of words
      mpirun -n "$np" /usr/bin/time -f "max_rss_kb %M" "$bin" run --problem "$problem" $settings \
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
      linear=${row##*,} row=${row%,*}
      case $row in true,*) ;; *)  # not verified: say why on stderr before the log goes
        echo "scale_benchmark: n=$n, $np processes, $solve: not verified; the end of its log:" >&2
        tail -n 5 "$dir.log" >&2 ;;
      esac
      echo "$n,$d,$np,$solve,$formulation,$row,$(echo "$end - $start" | bc),$rss,$linear,$problem,$load" | tee -a "$out"
    done
  done
done
rm -rf "$work"
