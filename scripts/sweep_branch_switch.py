#!/usr/bin/env python3
"""The branch switch of P2 (`arch-flat`) swept over what must not matter.

Runs `contactbench run --problem arch-flat --bifurcations switch` for every formulation that
traces paths, equation solver, arc length, eta case and BLAS thread count, and checks in the
records that the switch onto the asymmetric branch D succeeded and D was traced: exit status 0
(every step verified), the bifurcation point marked switched and no failed switch, the step off
it accepted and verified, the last step on branch 1, the saved states symmetric before the
switch and the asymmetric mode growing after it. Prints one table row a run and a closing
'N passed, N failed' line; exits 1 when any run fails.

Usage: sweep_branch_switch.py BINARY OUT_DIR [--quick] [--jobs N]
  --quick  the CI-sized matrix (tests/CMakeLists.txt); without it, the whole matrix
"""
import argparse
import csv
import itertools
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

SOLVERS = ["newton", "dogleg", "quasi-newton"]
ARC_LENGTHS = [0.05, 0.1, 0.2, 0.5]
ETAS = [1, 2, 3, 4]
THREADS = [1, 2]
# Whether the formulation takes --solver (and --eta): the suite's own equation formulations.
FORMULATIONS = {"implicit-fb": (True, True), "nonsmooth-fb": (True, False),
                "active-set": (True, False), "petsc-ssls": (False, False)}
SYMMETRIC = 1e-8      # asymmetry of a state on the symmetric branch (rounding)
ASYMMETRIC = 1e-3     # asymmetry of a state on branch D, just off C


def full_matrix():
    for name, (solvers, etas) in FORMULATIONS.items():
        for solver, theta, eta, threads in itertools.product(
                SOLVERS if solvers else [None], ARC_LENGTHS, ETAS if etas else [None],
                THREADS):
            yield name, solver, theta, eta, threads


def quick_matrix():
    """Every solver at the smallest and largest arc length, every eta case, every formulation
    and both thread counts, each at least once."""
    runs = [("implicit-fb", s, t, 1, 1) for s in SOLVERS for t in (0.05, 0.5)]
    runs += [("implicit-fb", "newton", 0.1, e, 2) for e in ETAS]
    runs += [(f, s, 0.2, None, 2) for f in ("nonsmooth-fb", "active-set")
             for s in ("newton", "quasi-newton")]
    runs += [("petsc-ssls", None, 0.1, None, 1)]
    return runs


def asymmetry(nodes):
    """The distance of a state from its mirror image about the vertical line half-way between
    the supports (a) and (b), the two nodes at y = 0: zero on P2's symmetric branch."""
    ref = {(round(float(n["x"]), 9), round(float(n["y"]), 9)): n for n in nodes}
    pos = {k: (k[0] + float(n["ux"]), k[1] + float(n["uy"])) for k, n in ref.items()}
    ends = sorted(k for k in ref if k[1] == 0.0)
    mid = 0.5 * (pos[ends[0]][0] + pos[ends[-1]][0])
    total = 0.0
    for k in ref:
        m = pos[(round(-k[0], 9), k[1])]
        total += (pos[k][0] + m[0] - 2 * mid) ** 2 + (pos[k][1] - m[1]) ** 2
    return (0.5 * total) ** 0.5


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def judge(out, status):
    """Why the run does not show a verified switch onto a growing asymmetric branch, or ''."""
    if status != 0:
        return f"exit status {status}"
    critical = rows(os.path.join(out, "critical.csv"))
    marked = [c for c in critical if c["kind"] == "bifurcation" and c["switched"] == "true"]
    if not marked or any("switch failed" in c["message"] for c in critical):
        return "no switch at a bifurcation point"
    steps = [s for s in rows(os.path.join(out, "steps.csv")) if s["accepted"] == "true"]
    off = [s for s in steps if s["branch_switch"] == "true"]
    if len(off) != 1 or off[0]["verified"] != "true":
        return "the step off the bifurcation point is not accepted and verified"
    if steps[-1]["branch"] != "1":
        return "the path does not end on branch 1"
    switch_step = int(off[0]["step"])
    saved = {}
    for n in rows(os.path.join(out, "snapshots.csv")):
        if n["label"] == "step":
            saved.setdefault(int(n["step"]), []).append(n)
    before = [asymmetry(v) for k, v in sorted(saved.items()) if k < switch_step]
    after = [asymmetry(v) for k, v in sorted(saved.items()) if k >= switch_step]
    if max(before, default=0.0) > SYMMETRIC:
        return f"a state before the switch is asymmetric ({max(before):.2e})"
    if len(after) < 2 or after[0] < ASYMMETRIC or not after[-1] > after[0]:
        return "the asymmetric mode does not grow after the switch: " + \
            ", ".join(f"{a:.3g}" for a in after)
    return ""


def built(binary):
    """The formulations this binary has (`contactbench list` marks the others 'not built')."""
    listing = subprocess.run([binary, "list"], capture_output=True, text=True,
                             check=True).stdout.splitlines()
    names = set()
    for line in listing:
        words = line.split()
        if line.startswith("  ") and words and words[0] in FORMULATIONS \
                and "(not built)" not in line:
            names.add(words[0])
    return names


def run(binary, root, case):
    name, solver, theta, eta, threads = case
    label = "-".join(str(x) for x in case if x is not None)
    out = os.path.join(root, label)
    steps = int(round(100 / theta))
    cmd = [binary, "run", "--problem", "arch-flat", "--formulation", name,
           "--bifurcations", "switch", "--arc-length", str(theta), "--steps", str(steps),
           "--save-every", str(steps // 20), "--out", out, "--overwrite"]
    if solver:
        cmd += ["--solver", solver]
    if eta:
        cmd += ["--eta", str(eta)]
    env = dict(os.environ, OPENBLAS_NUM_THREADS=str(threads))
    done = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True)
    why = judge(out, done.returncode)
    if not why and not os.path.exists(os.path.join(out, "steps.csv")):
        why = "no records"
    return case, why


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("out")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()
    cases = quick_matrix() if args.quick else list(full_matrix())
    have = built(args.binary)
    skipped = [c for c in cases if c[0] not in have]
    cases = [c for c in cases if c[0] in have]
    for name in sorted({c[0] for c in skipped}):
        print(f"branch switch: {name} is not built into {args.binary}: skipped", file=sys.stderr)
    os.makedirs(args.out, exist_ok=True)
    print("| formulation | solver | theta | eta | BLAS threads | switch onto D |")
    print("|---|---|---|---|---|---|")
    failed = 0
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for case, why in pool.map(lambda c: run(args.binary, args.out, c), cases):
            name, solver, theta, eta, threads = case
            failed += bool(why)
            print(f"| {name} | {solver or '-'} | {theta} | {eta or '-'} | {threads} | "
                  f"{why or 'verified, D traced'} |", flush=True)
    print(f"branch switch: {len(cases) - failed} passed, {failed} failed"
          + (f", {len(skipped)} skipped" if skipped else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
