#!/usr/bin/env bash
# The Siconos formulations on P1 `block` with one and two BLAS threads (issue 25, section 2;
# docs/backend-siconos.md, "Rounding"): for each n and formulation,
#   OPENBLAS_NUM_THREADS=T contactbench run --problem block --set n=N --formulation F --out DIR
# with T = 1 and 2, then a markdown table of the pivots (Lemke) or iterations (Newton) of each,
# "not" where the step was not verified, and a last line 'same: K of M' counting the (n,
# formulation) cells whose outcome (count and verified) agrees between the two thread counts.
# Exit status 1 when any differs or fails to verify, 2 on a usage error. About 10 to 40 s for the
# default sizes on a 2-core machine.
#
# Usage: scripts/investigation/p1_siconos_threads.sh [CONTACTBENCH_BINARY] OUT_DIR [N ...]
#   CONTACTBENCH_BINARY  default build/bin/contactbench
#   N ...                default 20 30 40 50 60 80 100
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
binary="$here/build/bin/contactbench"
if [[ $# -ge 1 && -x "$1" && ! -d "$1" ]]; then
  binary="$1"
  shift
fi
if [[ $# -lt 1 ]]; then
  echo "usage: $0 [CONTACTBENCH_BINARY] OUT_DIR [N ...]" >&2
  exit 2
fi
out="$1"
shift
sizes=("$@")
[[ ${#sizes[@]} -eq 0 ]] && sizes=(20 30 40 50 60 80 100)
formulations=(siconos-lemke siconos-newton-fb siconos-newton-min)
mkdir -p "$out" || exit 2

for n in "${sizes[@]}"; do
  for f in "${formulations[@]}"; do
    for t in 1 2; do
      dir="$out/$f-n$n-t$t"
      rm -rf "$dir"
      OPENBLAS_NUM_THREADS=$t "$binary" run --problem block --set "n=$n" --formulation "$f" \
        --out "$dir" >"$dir.log" 2>&1
    done
  done
done

python3 - "$out" "${sizes[*]}" "${formulations[*]}" <<'EOF'
import csv
import sys

out, sizes, formulations = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()


def outcome(f, n, t):
    try:
        with open(f"{out}/{f}-n{n}-t{t}/steps.csv", newline="") as handle:
            row = list(csv.DictReader(handle))[-1]
    except (OSError, IndexError):
        return ("no record", False)
    verified = row["verified"] == "true"
    return (row["iterations"] + ("" if verified else ", not"), verified)


print("| n | " + " | ".join(f"{f} (1 / 2 threads)" for f in formulations) + " |")
print("|---|" + "---|" * len(formulations))
same = total = 0
good = True
for n in sizes:
    cells = []
    for f in formulations:
        one, two = outcome(f, n, 1), outcome(f, n, 2)
        total += 1
        same += one == two
        good &= one == two and one[1] and two[1]
        cells.append(f"{one[0]} / {two[0]}")
    print(f"| {n} | " + " | ".join(cells) + " |")
print(f"same: {same} of {total}")
sys.exit(0 if good else 1)
EOF
