#!/usr/bin/env python3
"""The iterative linear solve's iteration budget (docs/scale-out.md, "Multigrid with supports"):

    /usr/bin/python3 tests/python/check_amg_budget.py CONTACTBENCH_BINARY

runs `dist-active-set --option linear=amg` on P1 with its top-left node held in x (n = 40,
scripts/supported_block.py) and on `hertz-3d` (8 x 8 x 8, symmetry supports), each from its
default start as in the table, and checks that each verifies within its budget of Krylov
iterations per Newton iteration (steps.csv's linear_solves over iterations): 40 for the
supported P1, 200 for hertz-3d. The table in docs/scale-out.md measured 28.0 and 135.6, and
the counts stay flat as the meshes are refined; before GAMG had whole nodes and the rigid modes
on supported bodies, P1 took 125 and hertz-3d failed (DIVERGED_LINEAR_SOLVE). A budget about 1.5
times the measured count guards against a return of either, not against rounding.

Exit status 0 when both hold, 1 when one fails (printed), and 77 (ctest's SKIP_RETURN_CODE) in a
build without the distributed formulations.
"""
import csv
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "scripts")
BUDGETS = {"p1-supported": 40.0, "hertz-3d": 200.0}


def available(binary):
    listing = subprocess.run([binary, "list"], capture_output=True, text=True, check=True).stdout
    return any(line.split()[:1] == ["dist-active-set"] and "not built" not in line
               for line in listing.splitlines())


def krylov_per_newton(binary, args, out):
    command = [binary, "run"] + args + ["--formulation", "dist-active-set", "--option",
                                        "linear=amg", "--out", out]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    with open(os.path.join(out, "steps.csv"), newline="") as f:
        steps = list(csv.DictReader(f))
    if done.returncode != 0 or len(steps) != 1 or steps[0]["verified"] != "true":
        return None, done.stderr.strip()
    newton, krylov = int(steps[0]["iterations"]), int(steps[0]["linear_solves"])
    return krylov / newton, f"{krylov} Krylov iterations in {newton} Newton iterations"


def main():
    binary = sys.argv[1]
    if not available(binary):
        print("skipped: built without the distributed formulations")
        return 77
    failures = 0
    with tempfile.TemporaryDirectory() as work:
        p1 = os.path.join(work, "p1.json")
        subprocess.run([sys.executable, os.path.join(SCRIPTS, "supported_block.py"), "p1", "40",
                        p1], check=True, stdout=subprocess.DEVNULL)
        runs = {"p1-supported": ["--problem-file", p1],
                "hertz-3d": ["--problem", "hertz-3d", "--set", "n=8", "--set", "nz=8"]}
        for name, args in runs.items():
            ratio, what = krylov_per_newton(binary, args, os.path.join(work, name))
            if ratio is None:
                print(f"{name}: not verified: {what}")
                failures += 1
            elif ratio > BUDGETS[name]:
                print(f"{name}: {ratio:.1f} Krylov iterations per Newton iteration, over the "
                      f"budget of {BUDGETS[name]:g} ({what})")
                failures += 1
            else:
                print(f"{name}: {ratio:.1f} per Newton iteration, budget {BUDGETS[name]:g} "
                      f"({what})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
