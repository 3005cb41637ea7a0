"""COMPARISON.md's section "Speed to the floor", from bench/speed_floor_benchmark.json
(bench/speed_floor_benchmark.cc, scripts/run_bench.sh): per case (problem, n), implicit-fb's
cold solve with its time split and its floor, its full route, and PETSc's petsc-ssls and
petsc-rsls, all from one run with the repetitions interleaved; the ratios are of the medians."""
import os

import numpy as np

from plotlib.aggregation import PROBLEM_LABEL, fmt, read_benchmarks

VARIANTS = ["implicit-fb", "implicit-fb-full", "petsc-ssls", "petsc-rsls"]
PETSC = ["petsc-ssls", "petsc-rsls"]
SPLIT = ["setup_s", "factorization_s", "iterations_s", "recovery_s"]


def rows(bench):
    """The benchmark's rows with problem, variant and n split out of run_name
    (<problem>/<variant>/n:<n>/...)."""
    b = bench[bench["run_name"].astype(str).str.match(r"^(block|hertz-3d)/")].copy()
    parts = b["run_name"].str.split("/")
    b["problem"], b["variant"] = parts.str[0], parts.str[1]
    b["n"] = parts.str[2].str.replace("n:", "", regex=False).astype(int)
    b = b[b["variant"].isin(VARIANTS)]
    # P1 first, then hertz-3d; each by n (the interleaved run writes them in random order).
    return b.sort_values(["problem", "n"], ascending=[True, True], kind="stable")


def timed(row):
    """'T s (min-max), K it' of a row, or None when it was not timed."""
    if row is None or row["error_occurred"]:
        return None
    low, high = row.get("seconds_min", np.nan), row.get("seconds_max", np.nan)
    spread = f" ({fmt(low)}-{fmt(high)})" if np.isfinite(low) and np.isfinite(high) else ""
    return f"{fmt(row['seconds'])} s{spread}, {fmt(row.get('iterations'), '.0f')} it"


def case_cells(g, reasons):
    """The table's cells for one case (the rows g of one problem and n)."""
    by = {r["variant"]: r for _, r in g.iterrows()}
    ours = by.get("implicit-fb")
    cells = []
    for v in VARIANTS:
        text = timed(by.get(v))
        if text is None and v in by:
            reason = str(by[v]["error_message"])
            reasons.setdefault(reason, len(reasons) + 1)
            text = f"({reasons[reason]})"
        cells.append(text or "")
    ok = ours is not None and not ours["error_occurred"]
    split = " / ".join(fmt(ours.get(k)) for k in SPLIT) if ok else ""
    floor = f"{fmt(ours.get('floor_s'))} s ({fmt(ours.get('time_over_floor'), '.2f')}x)" if ok \
        else ""
    petsc = [by[v]["seconds"] for v in PETSC if v in by and not by[v]["error_occurred"]]
    best = f"{fmt(min(petsc) / ours['seconds'], '.2f')}" if ok and petsc else "-"
    return cells[:1] + [split, floor] + cells[1:] + [best]


def section(results_dir):
    path = os.path.join(results_dir, "bench", "speed_floor_benchmark.json")
    if not os.path.exists(path):
        return []
    context, bench = read_benchmarks(path)
    b = rows(bench)
    if b.empty:
        return []
    start, end = context.get("load_avg"), context.get("load_avg_end")
    load = (f"load average (1 min) {start[0]:.2f} at the start"
            + (f" and {end[0]:.2f} at the end" if end else "")) if start else "load not recorded"
    clock = context.get("mhz_per_cpu")
    repetitions = int(b["repetitions"].max()) if "repetitions" in b else "?"
    out = ["## Speed to the floor (`speed_floor_benchmark`)", "",
           "One cold fixed-load solve by a fresh formulation, its repetitions interleaved at "
           "random with the other formulations' in one run: the median time with the range "
           f"(min-max) of {repetitions} repetitions "
           f"({clock if clock else '?'} MHz, {load}; one BLAS thread). implicit-fb is the "
           "default, Newton on the contact unknowns; its split is set-up (the patterns, the "
           "start, the first Jacobian, b~_c's forward sweep) / factorisation of A + D0 / "
           "Newton iterations / recovery of the interior, in seconds; its floor is one "
           "factorisation plus one forward and one backward sweep per Newton iteration, "
           "measured in the same solve, with the solve's time over it. `implicit-fb-full` is "
           "option `reduced_newton=0` (Newton on all unknowns). The last column is the faster "
           "PETSc formulation's median over implicit-fb's. Every timed answer passed the "
           "verdict (1e-8).", ""]
    reasons = {}
    out += ["| problem | n | d | implicit-fb | split s | floor | implicit-fb-full | petsc-ssls "
            "| petsc-rsls | best PETSc / implicit-fb |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for (problem, n), g in b.groupby(["problem", "n"], sort=False):
        d = g["d"].dropna()
        dofs = f"{int(d.iloc[0])}" if len(d) else "-"
        out.append(f"| {PROBLEM_LABEL.get(problem, problem)} | {n} | {dofs} | "
                   + " | ".join(case_cells(g, reasons)) + " |")
    out.append("")
    if reasons:
        out += ["Not timed:", ""] + [f"- ({k}) {m}" for m, k in reasons.items()] + [""]
    return out
