#!/usr/bin/env python3
"""The convergence table of `hertz-3d` (docs/problems.md): runs the problem on meshes n x n x n
and compares the contact radius and the peak pressure with Hertz's closed form.

    python3 scripts/hertz_convergence.py build/bin/contactbench OUTDIR [n ...]

Measured as src/problems/hertz.cc's MeasureHertzContact does (results/plotlib/solid3d.py, which
also writes the report's table from scripts/run_solid3d.sh's records): the radius from the second
moment of the contact reactions (sum |r| rho^2 / sum |r| = 2 a^2 / 5), the peak pressure as the
reaction of the node at the origin over its tributary area (a quarter of the first cell).
"""
import os
import subprocess
import sys

import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "results"))
from plotlib.solid3d import closed_form, measure  # noqa: E402


def main():
    binary, out = sys.argv[1], sys.argv[2]
    sizes = [int(n) for n in sys.argv[3:]] or [8, 12, 16, 24]
    a_ref, p_ref = closed_form(30.0, 50.0, 1000.0, 0.3)
    print(f"Hertz: a = {a_ref:.4f} mm, p0 = {p_ref:.3f} N/mm^2")
    print("| n x n x n | d | nc | a [mm] | error a | p0 [N/mm^2] | error p0 |")
    print("|---|---|---|---|---|---|---|")
    for n in sizes:
        directory = f"{out}/hertz-n{n}"
        subprocess.run([binary, "run", "--problem", "hertz-3d", "--formulation", "implicit-fb",
                        "--set", f"n={n}", "--set", f"nz={n}", "--out", directory,
                        "--overwrite"], check=True, capture_output=True)
        d = 3 * (n + 1) ** 3 - 2 * (n + 1) ** 2
        a, p0 = measure(pd.read_csv(f"{directory}/solution.csv"),
                        pd.read_csv(f"{directory}/contacts.csv"))
        print(f"| {n} | {d} | {(n + 1) ** 2} | {a:.4f} | {100 * (a / a_ref - 1):+.2f} % "
              f"| {p0:.3f} | {100 * (p0 / p_ref - 1):+.2f} % |")


if __name__ == "__main__":
    main()
