#!/usr/bin/env python3
"""The per-process cost model of the distributed solve (docs/scale-out.md, "Cost model"), fitted
to scale-benchmark records (scripts/scale_benchmark.sh) of one linear solve:

  memory per process (MiB) = m0 + a d + b d / p    (a: replicated on every process, b: divided)
  time per Newton iteration (s) = c d^k             (one fit per process count)

and what d = D would need on P processes from them. Prints a Markdown report; every figure in it
comes from the rows read (verified rows only). Times depend on the machine's load: the report
gives the load range of the rows it fits.

Usage: scripts/cost_model.py SOLVE D P CSV...
  SOLVE: amg or direct; e.g. amg 1e8 256 results/scale/p1-*.csv
"""
import csv
import sys

import numpy as np


def rows_of(paths, solve):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                if r["linear_solve"] == solve and r["verified"] == "true":
                    rows.append({"d": float(r["d"]), "p": int(r["processes"]),
                                 "mb": float(r["max_rss_mb_per_process"]),
                                 "newton": int(r["iterations"]), "solve_s": float(r["solve_s"]),
                                 "load": r.get("load_1min") or "", "source": path})
    return rows


def fit_memory(rows):
    design = np.array([[1.0, r["d"], r["d"] / r["p"]] for r in rows])
    target = np.array([r["mb"] for r in rows])
    coefficients, *_ = np.linalg.lstsq(design, target, rcond=None)
    worst = max(abs(design @ coefficients - target) / target)
    return coefficients, worst


def fit_time(rows):
    fits = {}
    for p in sorted({r["p"] for r in rows}):
        mine = [r for r in rows if r["p"] == p]
        if len({r["d"] for r in mine}) < 2:
            continue
        x = np.log([r["d"] for r in mine])
        y = np.log([r["solve_s"] / r["newton"] for r in mine])
        k, log_c = np.polyfit(x, y, 1)
        fits[p] = (float(np.exp(log_c)), float(k), len(mine))
    return fits


def report(solve, big_d, processes, paths):
    rows = rows_of(paths, solve)
    if len(rows) < 3 or len({r["p"] for r in rows}) < 2:
        sys.exit(f"cost_model: need verified {solve} rows on at least two process counts")
    (m0, a, b), worst = fit_memory(rows)
    times = fit_time(rows)
    print(f"Fitted to {len(rows)} verified `{solve}` runs, d = {min(r['d'] for r in rows):.0f} to "
          f"{max(r['d'] for r in rows):.0f}, p = {sorted({r['p'] for r in rows})}:\n")
    print(f"- memory per process: {m0:.0f} MiB + {a * 1024:.2f} KiB x d + {b * 1024:.2f} KiB x d "
          f"/ p (largest misfit {100 * worst:.0f} %)")
    for p, (c, k, n) in times.items():
        print(f"- time per Newton iteration on {p} process{'es' if p > 1 else ''}: "
              f"{c:.3g} s x d^{k:.2f} ({n} runs)")
    loads = sorted(float(r["load"]) for r in rows if r["load"])
    if loads:
        print(f"- load average at the runs' starts: {loads[0]:g} to {loads[-1]:g}")
    per_process = m0 + a * big_d + b * big_d / processes
    print(f"\nAt d = {big_d:.3g} on {processes} processes: {per_process / 1024:.1f} GiB per "
          f"process, of which {a * big_d / 1024:.1f} GiB replicated on every process "
          f"({per_process * processes / 1024 ** 2:.2f} TiB in all); without the replicated part "
          f"{(m0 + b * big_d / processes) / 1024:.1f} GiB.")
    if 1 in times:
        c, k, _ = times[1]
        print(f"One process's fit gives {c * big_d ** k:.3g} s per Newton iteration at d = "
              f"{big_d:.3g}, to divide by {processes} times the parallel efficiency.")


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    report(sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), sys.argv[4:])


if __name__ == "__main__":
    main()
