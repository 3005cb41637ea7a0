"""The headline figures: the section "Headline figures" of RESULTS_DIR/COMPARISON.md, one table
that README.md links to instead of typing figures by hand.

`section(results_dir, sets)` computes each figure from the records the rest of COMPARISON.md
reads (the comparison sets' steps, `bench/scaling_benchmark.json`) with the functions of
aggregation.py, so a figure here is the same number as the cell of the section it names:
  - per arch set (P2, P3): the steps implicit-fb verifies warm and from the report's cold start,
    and its median iterations over the accepted steps;
  - per arch set: the median time of an accepted warm step of each PETSc formulation over
    implicit-fb's (the column "median time, accepted");
  - P1's cold solve at each size of the scaling benchmark: each peer's time over implicit-fb's.
"""
import numpy as np

from plotlib import aggregation as cmp

ARCH_SETS = ("arch-flat", "arch-curved")
PETSC = ("petsc-rsls", "petsc-ssls")
P1_PEERS = ("petsc-rsls", "petsc-ssls", "siconos-lemke", "siconos-newton-fb",
            "siconos-newton-min")
P1_SIZES = (50, 400)
REFERENCE = "implicit-fb"


def _row(table, formulation, start):
    r = table[(table["formulation"] == formulation) & (table["start"] == start)]
    return r.iloc[0] if len(r) else None


def _set_rows(name, runs, steps):
    table, _, _, _ = cmp.aggregate(runs, steps)
    if not len(table):
        return []
    label = "%s (set `%s`)" % (cmp.PROBLEM_LABEL.get(name, name), name)
    rows = []
    warm, cold = _row(table, REFERENCE, "warm"), _row(table, REFERENCE, "cold")
    if warm is not None:
        rows.append(("%s: steps implicit-fb verifies warm; median iterations" % label,
                     "%d of %d; %s" % (warm["solved"], warm["steps"],
                                       cmp.fmt(warm["median_iterations"], ".0f"))))
    if cold is not None:
        rows.append(("%s: steps implicit-fb verifies from the report's cold start" % label,
                     "%d of %d" % (cold["solved"], cold["steps"])))
    if warm is not None:
        ratios = []
        for f in PETSC:
            r = _row(table, f, "warm")
            if r is not None and np.isfinite(r["median_time_ms"]):
                ratios.append("%s %s" % (f, cmp.fmt(r["median_time_ms"] / warm["median_time_ms"],
                                                    ".2g")))
        if ratios:
            rows.append(("%s: median time of an accepted warm step, over implicit-fb's" % label,
                         ", ".join(ratios)))
    return rows


def _p1_rows(results_dir):
    path = "%s/bench/scaling_benchmark.json" % results_dir
    try:
        _, bench = cmp.read_benchmarks(path)
    except FileNotFoundError:
        return []
    s = cmp.scaling_rows(bench)
    if s.empty:
        return []
    rows = []
    for n in P1_SIZES:
        at_n = s[(s["n"] == n) & ~s["error_occurred"]]
        ref = at_n[at_n["formulation"] == REFERENCE]
        if not len(ref):
            continue
        t_ref = ref["seconds"].iloc[0]
        ratios = ["%s %s" % (f, cmp.fmt(at_n[at_n["formulation"] == f]["seconds"].iloc[0] / t_ref,
                                        ".2g")) if (at_n["formulation"] == f).any() else
                  "%s not timed (see the table)" % f
                  for f in P1_PEERS if (s[s["n"] == n]["formulation"] == f).any()]
        if ratios:
            rows.append(("P1 block n = %d, cold solve (`scaling_benchmark`): time over "
                         "implicit-fb's (%s s)" % (n, cmp.fmt(t_ref)), ", ".join(ratios)))
    return rows


def section(results_dir, sets):
    """The section's markdown lines; `sets`: aggregation.comparison_sets' (name, runs, steps)."""
    rows = []
    for name, runs, steps in sets:
        if name in ARCH_SETS:
            rows += _set_rows(name, runs, steps)
    rows += _p1_rows(results_dir)
    if not rows:
        return []
    out = ["## Headline figures", "",
           "The figures README.md quotes, each computed from the records of the section named "
           "in it (a time ratio: of the same run, on the same machine).", "",
           "| figure | value |", "|---|---|"]
    out += ["| %s | %s |" % row for row in rows]
    return out + [""]
