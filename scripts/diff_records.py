#!/usr/bin/env python3
"""Compares two record directories (contactbench run/compare --out) file by file.

A restructuring or a speed change must leave the records bit-identical: every CSV cell the same
text, except the columns that measure wall time (their names contain "time"), run.json field by
field except what names the build, the command line, the clock or the wall time, and every
other file (VTK, .pvd) byte for byte. Prints each difference (file, row, column, both values) and
exits 1 when there is any, 0 when the two directories hold the same records.

Usage: scripts/diff_records.py OLD_DIR NEW_DIR
"""
import csv
import json
import pathlib
import sys


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


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    old_dir, new_dir = pathlib.Path(argv[1]), pathlib.Path(argv[2])
    for d in (old_dir, new_dir):
        if not d.is_dir():
            print(f"diff_records: {d} is not a directory", file=sys.stderr)
            return 2
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
