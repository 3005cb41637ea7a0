#!/usr/bin/env python3
"""Compares the runs of scripts/check_invariance.sh against their baseline.

OUT_DIR/plan.csv lists the runs (example, kind, perturbation, threads, linear solver,
directory); each run's directory holds the records of `contactbench run` and DIR.status its exit
status and start and end times. For every example the first perturbation of the plan is the
baseline. What must be invariant (docs/findings.md, "Invariance under rounding"):

- the exit status (0: every step verified; a path that stops must stop the same way);
- the accepted steps (steps.csv);
- the kinks (kinks.csv): their count, the pair of each, and the lambda of each to 1e-6
  relative;
- the limit and bifurcation points and stability changes (critical.csv): their count, the kind
  of each, and the lambda of each to 1e-6 relative;
- the branches: the branch switches and the branch of the last accepted step;
- for a fixed-load example (P1) the answer: solution.csv's displacements to 1e-6 of the largest.

A lambda is compared relative to the larger of the two values, or to 1e-3 of the largest
|lambda| of the baseline's path when that is larger (a point where the load passes zero).
Not invariants, reported for information: the largest difference of iterations between the
accepted steps of the same number, and for a path the distance of the final states (relative to
the largest displacement). Also checked: the run used the BLAS thread count asked for
(run.json's `blas`); a perturbation that did not take effect fails its row.

Prints a markdown table, one row per example x perturbation (the baseline's row gives its
values, the others what matched, what did not and by how much), and the closing line
'invariance: N passed, N failed' (the perturbation rows). Exits 1 when any row failed.

Usage: invariance.py OUT_DIR
"""
import csv
import json
import os
import re
import sys

TOL = 1e-6


def rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except FileNotFoundError:
        return []


def load(root, plan_row):
    """What one run of the plan recorded, reduced to what the comparison needs."""
    return load_run(os.path.join(root, plan_row["dir"]), plan_row["kind"],
                    int(plan_row["threads"]))


def run_kind(out):
    """"fixed" when every step of the run in `out` is a fixed-load solve (P1), else "path"."""
    steps = rows(os.path.join(out, "steps.csv"))
    return "fixed" if steps and all(s["constraint"] == "fixed-load" for s in steps) else "path"


def load_run(out, kind=None, threads=None):
    """What the run in directory `out` recorded, reduced to what the comparison needs. `kind`:
    "fixed" (one solve, its answer compared) or "path". The exit status and run time come from
    out.status (written by check_invariance.sh) or else from run.json's exit_status (no time);
    `threads`: the BLAS threads asked for (None: not checked)."""
    try:
        with open(os.path.join(out, "run.json")) as f:
            info = json.load(f)
    except (FileNotFoundError, ValueError):
        info = {}
    run = {"kind": kind or run_kind(out), "problem": ""}
    try:
        with open(out + ".status") as f:
            rc, t0, t1 = f.read().split()
        run["exit"], run["seconds"] = int(rc), float(t1) - float(t0)
    except (FileNotFoundError, ValueError):
        run["exit"], run["seconds"] = info.get("exit_status"), 0.0
    run["reason"] = info.get("reason", "no run.json")
    found = re.search(r"\((\d+) threads?\)", info.get("blas", ""))
    run["blas_threads"] = int(found.group(1)) if found else None
    run["threads"] = run["blas_threads"] if threads is None else threads
    steps = [s for s in rows(os.path.join(out, "steps.csv")) if s["accepted"] == "true"]
    run["accepted"] = len(steps)
    run["all_verified"] = all(s["verified"] == "true" for s in steps)
    run["iterations"] = {int(s["step"]): int(s["iterations"]) for s in steps}
    run["switches"] = sum(s["branch_switch"] == "true" for s in steps)
    run["branch"] = int(steps[-1]["branch"]) if steps else None
    lambdas = [abs(float(s["lambda"])) for s in steps]
    run["lambda_scale"] = max(lambdas, default=1.0) or 1.0
    kinks = rows(os.path.join(out, "kinks.csv"))
    run["kinks"] = [(k["pair"], float(k["lambda"])) for k in kinks]
    run["kinks_located"] = all(k["verified"] == "true" and k["between"] == "true" for k in kinks)
    run["critical"] = [(c["kind"], float(c["lambda"])) for c in
                       rows(os.path.join(out, "critical.csv"))]
    run["switch_failed"] = any("switch failed" in c["message"] for c in
                               rows(os.path.join(out, "critical.csv")))
    run["solution"] = {}
    for r in rows(os.path.join(out, "solution.csv")):
        if "node" in r:
            values = [float(r[c]) for c in ("ux", "uy", "uz") if c in r]
            run["solution"][r["node"]] = values
        else:  # an LCP: the unknowns
            run["solution"][r["index"]] = [float(r["z"])]
    return run


def relative(a, b, floor):
    return abs(a - b) / max(abs(a), abs(b), floor)


def fmt(x):
    return f"{x:.1e}"


def compare_points(base, other, floor, label):
    """(matched, cell) for two lists of (identity, lambda): the same identities in order and
    each lambda within TOL."""
    worst = 0.0
    for i, ((ka, la), (kb, lb)) in enumerate(zip(base, other)):
        rel = relative(la, lb, floor)
        if ka != kb or rel > TOL:
            what = f"{label} {ka} vs {kb}" if ka != kb else f"rel {fmt(rel)}"
            return False, (f"**{len(base)} vs {len(other)}: #{i + 1} differs "
                           f"({what}; lambda {la:.6g} vs {lb:.6g})**")
        worst = max(worst, rel)
    if len(base) != len(other):
        i = min(len(base), len(other))
        first = (base if len(base) > len(other) else other)[i]
        return False, (f"**{len(base)} vs {len(other)}: the first {i} agree to {fmt(worst)}; "
                       f"then {first[0]} at lambda {first[1]:.6g}**")
    return True, f"= ({fmt(worst)})" if base else "= (none)"


def kinds(critical):
    counts = {}
    for kind, _ in critical:
        counts[kind] = counts.get(kind, 0) + 1
    return ", ".join(f"{n} {k}" for k, n in sorted(counts.items())) or "none"


def exit_text(run):
    if run["exit"] is None:
        return "no status"
    if run["exit"] == 0 and run["all_verified"] and run["kinks_located"]:
        return "0, verified"
    return f"{run['exit']}: {run['reason']}"


def largest(solution):
    return max((abs(v) for vs in solution.values() for v in vs), default=0.0)


def solution_difference(base, other):
    """max |u - u_base| over the nodes, relative to the baseline's largest |u|; None when the
    two do not hold the same nodes."""
    if set(base) != set(other) or not base:
        return None
    diff = max(abs(a - b) for k in base for a, b in zip(base[k], other[k]))
    return diff / (largest(base) or 1.0)


def histogram(run):
    """{iterations: accepted steps that took that many}."""
    counts = {}
    for n in run["iterations"].values():
        counts[n] = counts.get(n, 0) + 1
    return counts


def histogram_moved(base, other):
    """Steps that moved between the iteration counts of the two runs' histograms: 1/2 sum_k
    |a_k - b_k| over every count k (exact counts, not the report's bins); one step that takes
    one iteration more moves one step."""
    a, b = histogram(base), histogram(other)
    return sum(abs(a.get(k, 0) - b.get(k, 0)) for k in set(a) | set(b)) / 2


def threads_differ(run):
    """Why the run's BLAS did not run the thread count asked for, or ''."""
    if run["blas_threads"] is None or run["blas_threads"] == run["threads"]:
        return ""
    return f"**BLAS ran {run['blas_threads']} threads, not {run['threads']}**"


def baseline_row(run):
    answer = f"max abs u {largest(run['solution']):.6g}" if run["kind"] == "fixed" else "-"
    branches = f"{run['switches']} switch(es), ends on {run['branch']}"
    if run["switch_failed"]:
        branches += ", a switch failed"
    return [threads_differ(run) or exit_text(run), str(run["accepted"]), f"{len(run['kinks'])}",
            kinds(run["critical"]), branches, answer, f"{run['seconds']:.1f} s"]


def compare(base, other):
    """(failures, cells) of a perturbed run against its baseline."""
    failed = []
    cells = []
    if threads_differ(base) or threads_differ(other):
        failed.append("threads")
        cells.append(threads_differ(other) or "**the baseline's BLAS threads**")
    elif exit_text(other) == exit_text(base):
        cells.append("=")
    else:
        failed.append("exit")
        cells.append(f"**{exit_text(other)}**")
    if other["accepted"] == base["accepted"]:
        cells.append("=")
    else:
        failed.append("steps")
        cells.append(f"**{base['accepted']} vs {other['accepted']}**")
    floor = 1e-3 * base["lambda_scale"]
    ok, cell = compare_points(base["kinks"], other["kinks"], floor, "pair")
    cells.append(cell)
    if not ok:
        failed.append("kinks")
    ok, cell = compare_points(base["critical"], other["critical"], floor, "kind")
    cells.append(cell)
    if not ok:
        failed.append("critical points")
    same = (other["switches"], other["branch"], other["switch_failed"]) == \
        (base["switches"], base["branch"], base["switch_failed"])
    if same:
        cells.append("=")
    else:
        failed.append("branches")
        cells.append(f"**{other['switches']} switch(es), ends on {other['branch']}"
                     + (", a switch failed" if other["switch_failed"] else "") + "**")
    diff = solution_difference(base["solution"], other["solution"])
    if base["kind"] == "fixed":
        if diff is not None and diff <= TOL:
            cells.append(f"= ({fmt(diff)})")
        else:
            failed.append("answer")
            cells.append("**different nodes**" if diff is None else f"**{fmt(diff)}**")
    else:
        cells.append("-")
    common = set(base["iterations"]) & set(other["iterations"])
    info = "-"
    if common:
        step = max(sorted(common),
                   key=lambda s: abs(base["iterations"][s] - other["iterations"][s]))
        delta = abs(base["iterations"][step] - other["iterations"][step])
        info = f"{delta}" + (f" (step {step})" if delta and base["kind"] == "path" else "")
        if base["kind"] == "path":
            info += "; final u " + ("-" if diff is None else fmt(diff))
    cells.append(info + f"; {other['seconds']:.1f} s")
    return failed, cells


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    root = sys.argv[1]
    plan = rows(os.path.join(root, "plan.csv"))
    if not plan:
        print(f"invariance: no runs in {root}/plan.csv", file=sys.stderr)
        return 2
    order, by_example = [], {}
    for p in plan:
        if p["example"] not in by_example:
            order.append(p["example"])
            by_example[p["example"]] = []
        by_example[p["example"]].append(p)
    print("| example | perturbation | exit status | accepted steps | kinks (largest rel. "
          "difference of lambda) | limit / bifurcation points | branches | answer (P1) | "
          "iterations: largest per-step difference (information); time |")
    print("|---|---|---|---|---|---|---|---|---|")
    passed = failed = 0
    for name in order:
        runs = by_example[name]
        base = load(root, runs[0])
        label = f"{runs[0]['perturbation']} ({runs[0]['threads']} thread, " \
                f"{runs[0]['linear_solver']})"
        print(f"| {name} | {label} | " + " | ".join(baseline_row(base)) + " |")
        for p in runs[1:]:
            bad, cells = compare(base, load(root, p))
            passed += not bad
            failed += bool(bad)
            label = p["perturbation"] + (f": {', '.join(bad)} differ" if bad else "")
            print(f"| {name} | {label} | " + " | ".join(cells) + " |")
    print(f"invariance: {passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
