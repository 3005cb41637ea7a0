#!/usr/bin/env python3
"""The summary check of the comparison sets (scripts/check_results.sh --comparison): compares a
short replay of a set with the committed set over the same steps, by what COMPARISON.md reports
of them.

For every set under NEW_DIR/compare/ (runs.csv and steps.csv of `contactbench compare`), the
committed set of the same name under OLD_DIR/compare/ is cut to the steps the new one replayed
(the first N of the same reference path), and both are aggregated by results/plotlib/
comparison.py's own `aggregate` (the code behind COMPARISON.md's tables). For each formulation x
start: the verified steps and the median iterations over them must be equal, except that a solve
stopped by the time limit (status time_limit, in either run) is decided by the machine's speed:
the count may then differ by the number of such solves, and the median by one iteration (or be
undefined in one run, none of whose solves verified). A problem set (problems.csv of `compare
--problem-dir`, the FCLIB files) is compared row by row: for each problem x formulation x start
the status must be equal and the iterations of a verified solve equal, unless either solve was
stopped by the time limit. Times are not compared. Prints each difference and exits 1 when
there is any.

Usage: scripts/diff_comparison.py OLD_DIR NEW_DIR   (each a results directory, holding compare/)
"""
import math
import os
import sys

import pandas

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "results"))
from plotlib import comparison  # noqa: E402  (Debian's pandas: run with /usr/bin/python3)


def timed_out(steps):
    """{(formulation, start): solves stopped by the time limit}."""
    t = steps[steps["status"] == "time_limit"]
    return t.groupby(["formulation", "start"]).size().to_dict()


def same_median(a, b, slack):
    """Equal medians; with `slack` (time-limited solves), within slack or undefined on one side
    (no solve of that run verified)."""
    if math.isnan(a) or math.isnan(b):
        return (math.isnan(a) and math.isnan(b)) or slack > 0
    return abs(a - b) <= slack


def diff_set(name, old, new, out):
    (old_runs, old_steps), (new_runs, new_steps) = old, new
    last = new_steps["step"].max()
    old_steps = old_steps[old_steps["step"] <= last]
    a, _, _, _ = comparison.aggregate(old_runs, old_steps)
    b, _, _, _ = comparison.aggregate(new_runs, new_steps)
    clock = timed_out(old_steps)
    for key, n in timed_out(new_steps).items():
        clock[key] = clock.get(key, 0) + n
    rows = a.merge(b, on=["formulation", "start"], how="outer", suffixes=("_old", "_new"),
                   indicator=True)
    for _, r in rows.iterrows():
        label = "%s: %s %s" % (name, r["formulation"], r["start"])
        if r["_merge"] != "both":
            out.append("%s: only in the %s records" % (
                label, "committed" if r["_merge"] == "left_only" else "new"))
            continue
        slack = clock.get((r["formulation"], r["start"]), 0)
        if abs(r["solved_old"] - r["solved_new"]) > slack or r["steps_old"] != r["steps_new"]:
            out.append("%s: verified %d of %d -> %d of %d (time-limited solves: %d)" % (
                label, r["solved_old"], r["steps_old"], r["solved_new"], r["steps_new"], slack))
        if not same_median(r["median_iterations_old"], r["median_iterations_new"],
                           1 if slack else 0):
            out.append("%s: median iterations %s -> %s" % (
                label, comparison.fmt(r["median_iterations_old"]),
                comparison.fmt(r["median_iterations_new"])))
    return len(rows)


def problem_sets(results):
    """{set name: problems.csv} of the problem sets under RESULTS/compare/."""
    root = os.path.join(results, "compare")
    found = {}
    for name in sorted(os.listdir(root)) if os.path.isdir(root) else []:
        path = os.path.join(root, name, "problems.csv")
        if os.path.isfile(path):
            found[name] = pandas.read_csv(path)
    return found


def diff_problem_set(name, old, new, out):
    key = ["problem", "formulation", "start"]
    rows = old.merge(new, on=key, how="outer", suffixes=("_old", "_new"), indicator=True)
    for _, r in rows.iterrows():
        label = "%s: %s %s %s" % (name, r["problem"], r["formulation"], r["start"])
        if r["_merge"] != "both":
            out.append("%s: only in the %s records" % (
                label, "committed" if r["_merge"] == "left_only" else "new"))
            continue
        if "time_limit" in (r["found_old"], r["found_new"]):
            continue
        if r["status_old"] != r["status_new"]:
            out.append("%s: %s -> %s" % (label, r["status_old"], r["status_new"]))
        elif r["status_new"] == "verified" and r["iterations_old"] != r["iterations_new"]:
            out.append("%s: iterations %d -> %d" % (
                label, r["iterations_old"], r["iterations_new"]))
    return len(rows)


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    old = {n: (r, s) for n, r, s in comparison.comparison_sets(argv[1])}
    new = {n: (r, s) for n, r, s in comparison.comparison_sets(argv[2])}
    new_problems = problem_sets(argv[2])
    if not new and not new_problems:
        print("diff_comparison: no comparison sets under %s/compare" % argv[2], file=sys.stderr)
        return 2
    out, compared = [], 0
    for name in new:
        if name not in old:
            out.append("%s: no committed set of that name" % name)
            continue
        compared += diff_set(name, old[name], new[name], out)
    old_problems = problem_sets(argv[1])
    for name, table in new_problems.items():
        if name not in old_problems:
            out.append("%s: no committed problem set of that name" % name)
            continue
        compared += diff_problem_set(name, old_problems[name], table, out)
    for line in out:
        print(line)
    if out:
        print("diff_comparison: %d difference(s)" % len(out), file=sys.stderr)
        return 1
    print("diff_comparison: %d formulation x start runs and problem x formulation x start solves "
          "of %d sets agree (verified steps, median iterations; statuses, iterations)"
          % (compared, len(new) + len(new_problems)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
