#!/usr/bin/env python3
"""Compares the answers of two runs of the same problem (contactbench run --out), e.g. a serial run
and a distributed one (docs/scale-out.md): the same accepted steps, every one verified, and per
step the load factor, the control displacement and every node's displacement equal to `--rel`
(default 1e-6) of their largest magnitude over the run (for the control displacement, of the
largest of it and the nodes' displacements: a control node that barely moves, as under a fixed
load, is measured against the body's displacements, not against its own rounding). The two runs
may take different Newton iterates (the serial solver and PETSc's SNES), so their answers agree
to the solvers' tolerance, not bit for bit; the verdict judges each to 1e-8 (its default
tolerance).

Prints the largest differences and exits 1 when the answers differ, 0 when they agree.

Usage: scripts/compare_answers.py SERIAL_DIR OTHER_DIR [--rel R]
"""
import csv
import pathlib
import sys


def rows(directory, name):
    with open(pathlib.Path(directory) / name, newline="") as f:
        return list(csv.DictReader(f))


def accepted_steps(directory):
    return [r for r in rows(directory, "steps.csv") if r["accepted"] == "true"]


def largest(values):
    return max((abs(v) for v in values), default=0.0) or 1.0


def compare(a_dir, b_dir, rel):
    problems = []
    a, b = accepted_steps(a_dir), accepted_steps(b_dir)
    if len(a) != len(b):
        problems.append(f"accepted steps: {len(a)} against {len(b)}")
    for label, steps in (("first", a), ("second", b)):
        unverified = [r["step"] for r in steps if r["verified"] != "true"]
        if unverified:
            problems.append(f"{label} run: steps {unverified} not verified")
    sol_a, sol_b = rows(a_dir, "solution.csv"), rows(b_dir, "solution.csv")
    if len(sol_a) != len(sol_b):
        problems.append(f"solution.csv: {len(sol_a)} rows against {len(sol_b)}")
    columns = [c for c in ("ux", "uy", "uz") if sol_a and c in sol_a[0]]
    displacement_scale = largest(float(r[c]) for r in sol_a for c in columns)
    for column in ("lambda", "control_disp"):
        scale = largest(float(r[column]) for r in a)
        if column == "control_disp":
            scale = max(scale, displacement_scale)
        worst = max((abs(float(x[column]) - float(y[column])) for x, y in zip(a, b)), default=0.0)
        print(f"{column}: largest difference {worst:.3g} (scale {scale:.3g})")
        if worst > rel * scale:
            problems.append(f"{column} differs by {worst:.3g} > {rel} * {scale:.3g}")
    worst = max((abs(float(x[c]) - float(y[c])) for x, y in zip(sol_a, sol_b) for c in columns),
                default=0.0)
    print(f"displacements: largest difference {worst:.3g} (scale {displacement_scale:.3g})")
    if worst > rel * displacement_scale:
        problems.append(f"displacements differ by {worst:.3g} > {rel} * {displacement_scale:.3g}")
    return problems


def main(argv):
    rel = 1e-6
    if "--rel" in argv:
        k = argv.index("--rel")
        rel = float(argv[k + 1])
        argv = argv[:k] + argv[k + 2:]
    if len(argv) != 3:
        print(__doc__)
        return 2
    problems = compare(argv[1], argv[2], rel)
    for p in problems:
        print("DIFFERENT:", p)
    if not problems:
        print("same answers")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
