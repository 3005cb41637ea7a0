#!/usr/bin/env python3
"""Compares two record directories (contactbench run/compare --out) file by file.

A restructuring or a speed change must leave the records bit-identical: every CSV cell the same
text, except the columns that measure wall time (their names contain "time"), run.json field by
field except what names the build, the command line, the clock or the wall time, and every
other file (VTK, .pvd) byte for byte. Prints each difference (file, row, column, both values) and
exits 1 when there is any, 0 when the two directories hold the same records.

With --invariants, it compares what must not move between two machines or two builds that
compute the same thing (scripts/check_results.sh): every run directory (one holding run.json and
steps.csv) under OLD_DIR against the one at the same place under NEW_DIR, by the comparison of
the invariance check (scripts/invariance.py: the exit status and its reason, the accepted steps,
the kinks, limit and bifurcation points and their lambdas to 1e-6 relative, the branch switches
and the last branch exactly, a fixed-load solve's answer to 1e-6 of its largest displacement),
and the iteration histogram of the accepted steps within HISTOGRAM_TOLERANCE_* (a fixed-load
solve's iterations within FIXED_ITERATIONS_TOLERANCE; below); timings and every other column
are not compared.

Usage: scripts/diff_records.py [--invariants] OLD_DIR NEW_DIR
"""
import csv
import json
import os
import pathlib
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import invariance  # noqa: E402  (the one comparison of invariants, beside this script)

# How many accepted steps of a path may move between iteration counts (a step taking one
# iteration more or less) before its histogram counts as moved: the larger of
# HISTOGRAM_TOLERANCE_STEPS and HISTOGRAM_TOLERANCE_SHARE of the path's steps; a fixed-load
# solve's iterations may differ by FIXED_ITERATIONS_TOLERANCE. Chosen from the invariance check's
# perturbations, which stand in for another CPU's BLAS kernels (docs/findings.md, "Reproduction
# check": two BLAS threads move no step; another sparse factorisation up to 0.56% of a path's
# steps where the invariants hold, and P1's eta case 3 by up to 4 iterations).
HISTOGRAM_TOLERANCE_STEPS = 2
HISTOGRAM_TOLERANCE_SHARE = 0.01
FIXED_ITERATIONS_TOLERANCE = 1


def timing_column(name):
    return "time" in name


def diff_csv(old, new, label, out):
    with open(old, newline="") as a, open(new, newline="") as b:
        rows_a, rows_b = list(csv.reader(a)), list(csv.reader(b))
    if not rows_a or not rows_b:
        if rows_a != rows_b:
            out.append(f"{label}: one file is empty")
        return
    header = rows_a[0]
    if header != rows_b[0]:
        out.append(f"{label}: headers differ:\n  {header}\n  {rows_b[0]}")
        return
    if len(rows_a) != len(rows_b):
        out.append(f"{label}: {len(rows_a) - 1} rows against {len(rows_b) - 1}")
    for i, (ra, rb) in enumerate(zip(rows_a[1:], rows_b[1:]), start=1):
        for column, va, vb in zip(header, ra, rb):
            if va != vb and not timing_column(column):
                out.append(f"{label}: row {i}, {column}: {va} -> {vb}")
                if len(out) > 200:
                    return


# run.json's fields that differ between two runs of the same records: the build and the
# libraries, the BLAS and the machine it ran on and the machine's load, the command line (it
# names the output directory), what it reran, when it started and how long it took.
RUN_JSON_UNCOMPARED = {"version", "commit", "build", "libraries", "blas", "machine",
                       "load_average", "command_line", "rerun_of", "started_at", "wall_time_s"}


def without_paths(run):
    """run.json with the paths its inputs were read from left out: a rerun reads the copies
    (the copies' names and SHA-256 are still compared, and a named problem's name)."""
    for item in run.get("inputs", []):
        item.pop("source", None)
    source = run.get("problem_source", "")
    if source.startswith("--problem-file "):
        run["problem_source"] = "--problem-file"
    return run


def diff_run_json(old, new, label, out):
    a = without_paths(json.loads(old.read_text()))
    b = without_paths(json.loads(new.read_text()))
    for key in sorted((set(a) | set(b)) - RUN_JSON_UNCOMPARED):
        if a.get(key) != b.get(key):
            out.append(f"{label}: {key}: {a.get(key)!r} -> {b.get(key)!r}")


def run_dirs(root):
    """The directories under root (relative) that hold one run's records."""
    return {p.parent.relative_to(root) for p in root.rglob("run.json")
            if (p.parent / "steps.csv").is_file()}


def histogram_tolerance(run):
    return max(HISTOGRAM_TOLERANCE_STEPS, HISTOGRAM_TOLERANCE_SHARE * run["accepted"])


def diff_iterations(base, other, label, out):
    """The iteration counts: a fixed-load solve's within FIXED_ITERATIONS_TOLERANCE, a path's
    histogram within histogram_tolerance moved steps."""
    if base["kind"] == "fixed":
        a, b = sum(base["iterations"].values()), sum(other["iterations"].values())
        if abs(a - b) > FIXED_ITERATIONS_TOLERANCE:
            out.append(f"{label}: iterations {a} -> {b} (tolerance "
                       f"{FIXED_ITERATIONS_TOLERANCE})")
        return
    moved, limit = invariance.histogram_moved(base, other), histogram_tolerance(base)
    if moved > limit:
        a, b = invariance.histogram(base), invariance.histogram(other)
        out.append(f"{label}: iteration histogram: {moved:g} of {base['accepted']} steps moved "
                   f"(tolerance {limit:g}): {dict(sorted(a.items()))} -> "
                   f"{dict(sorted(b.items()))}")


# The columns of invariance.compare's cells, in order.
INVARIANT_COLUMNS = ("exit status", "accepted steps", "kinks", "limit / bifurcation points",
                     "branches", "answer")


def diff_run(old, new, label, out):
    base, other = invariance.load_run(str(old)), invariance.load_run(str(new))
    failed, cells = invariance.compare(base, other)
    if failed:
        committed = dict(zip(INVARIANT_COLUMNS, invariance.baseline_row(base)))
        moved = [f"{name}: {cell.strip('*')}" + (f" (was: {committed[name]})"
                                                 if name in ("exit status", "branches") else "")
                 for name, cell in zip(INVARIANT_COLUMNS, cells) if cell.startswith("**")]
        out.append(f"{label}: {', '.join(failed)} differ: " + "; ".join(moved))
    diff_iterations(base, other, label, out)


def diff_invariants(old_dir, new_dir):
    old_runs, new_runs = run_dirs(old_dir), run_dirs(new_dir)
    out = [f"only in {old_dir}: {p}" for p in sorted(old_runs - new_runs)]
    out += [f"only in {new_dir}: {p}" for p in sorted(new_runs - old_runs)]
    for rel in sorted(old_runs & new_runs):
        diff_run(old_dir / rel, new_dir / rel, str(rel), out)
    for line in out:
        print(line)
    if out:
        print(f"diff_records: {len(out)} difference(s) in the invariants", file=sys.stderr)
        return 1
    print(f"diff_records: {len(old_runs)} runs agree in their invariants (iteration histograms "
          f"within max({HISTOGRAM_TOLERANCE_STEPS}, {HISTOGRAM_TOLERANCE_SHARE:g} x steps) moved "
          f"steps, a fixed-load solve's iterations within {FIXED_ITERATIONS_TOLERANCE})")
    return 0


def main(argv):
    invariants = "--invariants" in argv[1:2]
    if invariants:
        argv = argv[:1] + argv[2:]
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    old_dir, new_dir = pathlib.Path(argv[1]), pathlib.Path(argv[2])
    for d in (old_dir, new_dir):
        if not d.is_dir():
            print(f"diff_records: {d} is not a directory", file=sys.stderr)
            return 2
    if invariants:
        return diff_invariants(old_dir, new_dir)
    old_files = {p.relative_to(old_dir) for p in old_dir.rglob("*") if p.is_file()}
    new_files = {p.relative_to(new_dir) for p in new_dir.rglob("*") if p.is_file()}
    out = [f"only in {old_dir}: {p}" for p in sorted(old_files - new_files)]
    out += [f"only in {new_dir}: {p}" for p in sorted(new_files - old_files)]
    for rel in sorted(old_files & new_files):
        a, b = old_dir / rel, new_dir / rel
        if rel.suffix == ".csv":
            diff_csv(a, b, str(rel), out)
        elif rel.name == "run.json":
            diff_run_json(a, b, str(rel), out)
        elif a.read_bytes() != b.read_bytes():
            out.append(f"{rel}: bytes differ")
    for line in out[:200]:
        print(line)
    if out:
        print(f"diff_records: {len(out)} difference(s)", file=sys.stderr)
        return 1
    print(f"diff_records: {len(old_files)} files identical (time columns aside)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
