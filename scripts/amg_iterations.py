#!/usr/bin/env python3
"""Krylov iterations per Newton iteration of the iterative linear solve (linear=amg) as meshes
are refined (docs/scale-out.md, "Multigrid with supports"): one run per problem and size of
`dist-active-set --option linear=amg`, on PROCESSES processes, one CSV row each: problem, size,
d (free displacement dofs), processes, steps, verified steps, Newton iterations and Krylov
iterations summed over every attempt of every step (steps.csv's iterations and linear_solves),
their ratio, and
the wall time. Iteration counts do not depend on the machine's load; the wall time does.

The 2-D Hertz rows mesh examples/hertz-2d.geo with Gmsh (`gmsh -2 -clscale S`, S = 2, 1, 0.5,
0.25), installed here if missing (scripts/packages.txt, job `scale`).

Usage: scripts/amg_iterations.py CONTACTBENCH OUT.csv [PROCESSES [PROBLEM...]]
  PROBLEM: p1-supported, hertz-2d, hertz-3d, plate-3d (default: all four)
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PROBLEMS = ("p1-supported", "hertz-2d", "hertz-3d", "plate-3d")


def hertz(n):
    # The graded box refined in every direction (nz = n); d = 3 (n+1)^3 less the two symmetry
    # faces' normal components.
    return ["--problem", "hertz-3d", "--set", f"n={n}", "--set", f"nz={n}"], \
        3 * (n + 1) ** 3 - 2 * (n + 1) ** 2


def plate(nx):
    # plate-3d refined in every direction from its 16 x 2 x 2 default, 0.01 m above the
    # cylinder (its default 0.2) so that contact closes in the first step; three steps.
    ny = nz = nx // 8
    return ["--problem", "plate-3d", "--set", f"nx={nx}", "--set", f"ny={ny}", "--set", f"nz={nz}",
            "--set", "clearance=0.01", "--set", "steps=3"], 3 * (nx + 1) * (ny + 1) * (nz + 1) - \
        2 * 3 * (ny + 1) * (nz + 1)


def supported_p1(n, work):
    # P1 with its top-left node held in x (scripts/supported_block.py).
    path = os.path.join(work, f"p1-{n}.json")
    subprocess.run([sys.executable, os.path.join(HERE, "supported_block.py"), "p1", str(n), path],
                   check=True, stdout=subprocess.DEVNULL)
    return ["--problem-file", path], 2 * (n + 1) ** 2 - 1


def hertz_2d(scale, work):
    # examples/hertz-2d.json on its .geo meshed with Gmsh's size factor `scale`; d = 2 nodes
    # less the axis' x components.
    folder = os.path.join(work, f"hertz-2d-{scale}")
    os.makedirs(folder)
    examples = os.path.join(HERE, "..", "examples")
    shutil.copy(os.path.join(examples, "hertz-2d.json"), folder)
    mesh = os.path.join(folder, "hertz-2d.msh")
    subprocess.run(["gmsh", "-2", "-clscale", str(scale), os.path.join(examples, "hertz-2d.geo"),
                    "-o", mesh], check=True, stdout=subprocess.DEVNULL)
    nodes, axis = mesh_counts(mesh)
    return ["--problem-file", os.path.join(folder, "hertz-2d.json")], 2 * nodes - axis


def mesh_counts(mesh):
    # The number of nodes of a Gmsh 4.1 mesh and of those on x = 0 (the symmetry axis).
    with open(mesh) as f:
        lines = f.read().split("\n")
    start = lines.index("$Nodes")
    blocks, nodes = int(lines[start + 1].split()[0]), int(lines[start + 1].split()[1])
    axis, at = 0, start + 2
    for _ in range(blocks):
        count = int(lines[at].split()[3])
        for line in lines[at + 1 + count:at + 1 + 2 * count]:
            axis += float(line.split()[0]) == 0.0
        at += 1 + 2 * count
    return nodes, axis


def cases(work, problems):
    if "p1-supported" in problems:
        for n in (20, 40, 80, 160):
            yield ("p1-supported", n) + supported_p1(n, work)
    if "hertz-2d" in problems:
        for scale in (2, 1, 0.5, 0.25):
            yield ("hertz-2d", scale) + hertz_2d(scale, work)
    if "hertz-3d" in problems:
        for n in (8, 12, 16, 20):
            yield ("hertz-3d", n) + hertz(n)
    if "plate-3d" in problems:
        for nx in (16, 32, 64):
            yield ("plate-3d", nx) + plate(nx)


def run(binary, args, processes, out_dir):
    launcher = ["mpirun", "-n", str(processes)] if processes > 1 else []
    command = launcher + [binary, "run"] + args + [
        "--formulation", "dist-active-set", "--option", "linear=amg", "--out", out_dir]
    start = time.monotonic()
    subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    wall = time.monotonic() - start
    records = os.path.join(out_dir, "steps.csv")
    if not os.path.exists(records):  # refused before its first step: a row of zeros
        return [], wall
    with open(records, newline="") as f:
        return list(csv.DictReader(f)), wall


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    binary, out = sys.argv[1], sys.argv[2]
    processes = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    problems = set(sys.argv[4:]) or set(PROBLEMS)
    if not problems <= set(PROBLEMS):
        sys.exit(f"amg_iterations: unknown problem(s) {sorted(problems - set(PROBLEMS))}; "
                 f"valid: {', '.join(PROBLEMS)}")
    if "hertz-2d" in problems:
        subprocess.run([os.path.join(HERE, "install_packages.sh"), "scale"], check=True)
    os.environ.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    fields = ["problem", "size", "d", "processes", "steps", "verified_steps", "newton", "krylov",
              "krylov_per_newton", "wall_s"]
    with tempfile.TemporaryDirectory() as work, open(out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        for problem, size, args, d in cases(work, problems):
            steps, wall = run(binary, args, processes, os.path.join(work, f"{problem}-{size}"))
            accepted = [s for s in steps if s["accepted"] == "true"]
            newton = sum(int(s["iterations"]) for s in steps)  # every attempt's solves
            krylov = sum(int(s["linear_solves"]) for s in steps)
            writer.writerow({
                "problem": problem, "size": size, "d": d, "processes": processes,
                "steps": len(accepted),
                "verified_steps": sum(s["verified"] == "true" for s in accepted),
                "newton": newton, "krylov": krylov,
                "krylov_per_newton": f"{krylov / newton:.1f}" if newton else "nan",
                "wall_s": f"{wall:.1f}"})
            f.flush()


if __name__ == "__main__":
    main()
