"""The readings of the report's figure: the section "Readings of the report's figure" of
RESULTS_DIR/REPORT.md and its figure.

`section(results_dir)` reads the records of scripts/run_readings.sh,
  results_dir/readings/index.csv                 every run: reading, problem, solver, dir,
                                                 settings, exit status
  results_dir/readings/<reading>/arch-flat/      P2 (Newton), critical points located
  results_dir/readings/<reading>/arch-flat-qn/   P2 (quasi-Newton)
  results_dir/readings/<reading>/arch-curved/    P3 (quasi-Newton)
  results_dir/readings/invariance/<name>/        the default P2 at other arc lengths and units
and returns the section's markdown lines (None when there are no such records), writing its
figure into results_dir/figures/reproduction/. For each reading: P2's limit point B (smooth or
at a kink, and which contact changes there), the order of B and the bifurcation point C, the
kinks before B and over the path, the iteration counts against Table 1's statement, and P3's
histogram against Table 2 with a distance between the two, each count also rescored at the
report-like stopping test `REPORT_LIKE_TOL` from the recorded residual histories.
"""
import os
import shutil

import numpy as np
import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

from plotlib import reproduction as rep  # noqa: E402

# The equation solvers stop at ||F||_inf <= 1e-10 (src/solvers/equation_solver.h); a report-like
# test, looser by a factor 30, rescored from iterations.csv.
SUITE_TOL = 1e-10
REPORT_LIKE_TOL = 3e-9
REPORT_TABLE_1 = {"two_iterations": 273}  # "2 iterations at 273 steps, at most 4 at almost all"
COMMAND = "bash scripts/run_readings.sh && /usr/bin/python3 results/plot.py"


# --- the measures, on the records of one run --------------------------------------------------

def rescored_iterations(steps, iterations, tol):
    """Iterations each accepted step would have taken with the stopping test ||F||_inf <= tol:
    the first recorded iteration of its accepted attempt whose residual_inf meets tol (the
    recorded count when none does, as for a stagnated step the verdict accepted). A Series by
    step. The looser test would also start the next step from a slightly different state; that
    second-order effect is not in a rescore."""
    acc = steps[steps["accepted"] == 1]
    it = iterations.merge(acc[["step", "attempt"]], on=["step", "attempt"])
    met = it[it["residual_inf"] <= tol].groupby("step")["iteration"].min()
    counts = acc.set_index("step")["iterations"].astype(int)
    return met.reindex(counts.index).fillna(counts).astype(int)


def table_distance(counts, report):
    """Total variation distance between two histograms, each normalised by its own total:
    1/2 sum |p_k - q_k| over the union of their bins; 0 for the same shape, 1 for disjoint.
    `counts`, `report`: {iterations: steps}."""
    keys = set(counts) | set(report)
    n, m = float(sum(counts.values())), float(sum(report.values()))
    if n == 0 or m == 0:
        return float("nan")
    return 0.5 * sum(abs(counts.get(k, 0) / n - report.get(k, 0) / m) for k in keys)


def binned(iterations):
    """{iterations: steps} with the bins of the report's tables (rep.HISTOGRAM_BINS)."""
    h = rep._histogram(pd.DataFrame({"iterations": np.asarray(iterations)}))
    return {k: int(v) for k, v in h.items() if v}


def describe_pair(pair, num_pairs, upper_nodes):
    """The pair's node and obstacle, by the pair order of src/problems/arch.cc: the upper nodes
    other than (a), (b) against the upper obstacle, then the lower nodes against the upper
    obstacle, then against the lower one."""
    inner_upper = upper_nodes - 2
    lower = (num_pairs - inner_upper) // 2
    if pair < inner_upper:
        return "upper node %d / upper obstacle" % (pair + 1)
    k = (pair - inner_upper) % lower
    # In node spacings: the aligned topologies have no centre node, their middle two are 0.5 off.
    off = abs(2 * k + 1 - lower) / 2.0
    where = "centre" if off == 0 else "%g from the centre" % off
    obstacle = "upper" if pair < inner_upper + lower else "lower"
    return "lower node %s / %s obstacle" % (where, obstacle)


def critical_points(run):
    """(B, C, first instability): the first limit point, the first bifurcation point and the
    first critical point that is not a limit point (a bifurcation point or a change of the
    number of unstable modes at a contact change), each a row of critical.csv or None."""
    c = run["critical"]
    if c is None or not len(c):
        return None, None, None
    c = c.sort_values(["step", "lambda"], kind="stable")

    def first(rows):
        return rows.iloc[0] if len(rows) else None
    return (first(c[c["kind"] == "limit"]), first(c[c["kind"] == "bifurcation"]),
            first(c[c["kind"] != "limit"]))


def _before(a, b):
    """Whether critical row a comes before b on the path: by step, then (both in one step, on
    the rising part before B) by lambda."""
    return (a["step"], a["lambda"]) < (b["step"], b["lambda"])


def order_of_b_and_c(b, c):
    if b is None and c is None:
        return "neither on the path"
    if b is None:
        return "C only"
    if c is None:
        return "B only (no C on the path)"
    first, second = ("C", "B") if _before(c, b) else ("B", "C")
    if b["step"] == c["step"]:
        apart = abs(b["lambda"] - c["lambda"])
        return "%s before %s, %.1e apart in lambda" % (first, second, apart)
    return "%s before %s (steps %d, %d)" % (first, second, min(b["step"], c["step"]),
                                            max(b["step"], c["step"]))


def located_kinks(run):
    k = run["kinks"]
    if k is None:
        return k
    return k[(k["verified"] == 1) & (k["between"] == 1)]


def p2_measures(run):
    """The P2 columns of the readings table for one run."""
    acc = rep._accepted(run)
    b, c, first_instability = critical_points(run)
    kinks = located_kinks(run)
    m = {"steps": len(acc), "kinks": len(kinks) if kinks is not None else 0}
    m["B"] = b
    m["order"] = order_of_b_and_c(b, c)
    m["kinks_before_B"] = (int((kinks["step"] <= b["step"]).sum())
                           if b is not None and kinks is not None else None)
    earlier = first_instability is not None and b is not None and _before(first_instability, b)
    m["instability_before_B"] = first_instability if earlier else None
    m["B_pair"] = None
    if b is not None and b["nonsmooth"] and kinks is not None:
        # The kinks at B: located between the steps around it, at B's lambda.
        near = kinks["step"].between(b["step"] - 1, b["step"])
        same = (kinks["lambda"] - b["lambda"]).abs() <= 1e-9 * max(1.0, abs(b["lambda"]))
        num_pairs = int(rep._parameter(run, "num_pairs", "0"))
        upper_nodes = int(rep._parameter(run, "upper_nodes", "0"))
        described = [describe_pair(int(q), num_pairs, upper_nodes)
                     for q in kinks[near & same]["pair"]]
        if described:
            m["B_pair"] = ", ".join("%s (x%d)" % (d, described.count(d)) if described.count(d) > 1
                                    else d for d in dict.fromkeys(described))
    return m


def counts_at(run, tol):
    """Iterations per accepted step at the stopping test tol: as recorded at the suite's own,
    rescored at any other (from iterations.csv, or from the thinned records' rescored.csv)."""
    if tol == SUITE_TOL:
        return rep._accepted(run)["iterations"].astype(int)
    if run["iterations"] is None and run.get("rescored") is not None:
        return run["rescored"].set_index("step")[_rescored_column(tol)].astype(int)
    return rescored_iterations(run["steps"], run["iterations"], tol)


def table_1_measures(run, tol):
    """Table 1's statement at the stopping test tol: steps with 2 iterations, the share of
    steps with at most 4, the most iterations."""
    counts = counts_at(run, tol)
    return {"steps": len(counts), "two": int((counts == 2).sum()),
            "at_most_4": float((counts <= 4).mean()) if len(counts) else float("nan"),
            "max": int(counts.max()) if len(counts) else 0}


def table_2_measures(run, tol):
    """The histogram in Table 2's bins at the stopping test tol and its distance to Table 2."""
    hist = binned(counts_at(run, tol))
    return {"hist": hist, "distance": table_distance(
        hist, {str(k): v for k, v in rep.REPORT_TABLE_2.items()})}


# --- the thinned records -----------------------------------------------------------------------

# What the section reads of a run, kept by thin_run: the accepted steps' columns below, the
# kinks, critical points, cells and parameters whole, run.json, and the iterations rescored at
# every stopping test the section uses (rescored.csv instead of iterations.csv).
THIN_STEP_COLUMNS = ("problem", "solver", "step", "lambda", "control_disp", "iterations",
                     "verified", "attempt", "accepted", "constraint", "branch", "branch_switch")
THIN_KEPT_FILES = ("kinks.csv", "critical.csv", "cells.csv", "parameters.csv", "run.json",
                   "steps.csv", "rescored.csv")


def _rescored_column(tol):
    return "iterations_at_%g" % tol


def thin_run(run_dir):
    """Rewrites the records of one readings run in place to what the section reads (about a
    tenth of them): steps.csv's accepted rows and THIN_STEP_COLUMNS, rescored.csv (each
    accepted step's iterations at every stopping test of SWEEP and REPORT_LIKE_TOL) instead
    of iterations.csv; the other files of THIN_KEPT_FILES as they are; the rest removed. The
    values are the recorded text, so the section reads the same numbers as from the records."""
    steps_path = os.path.join(run_dir, "steps.csv")
    if not os.path.isfile(steps_path) or os.path.getsize(steps_path) == 0:
        return  # a run that recorded no step: nothing to thin, what it wrote is kept
    text = pd.read_csv(steps_path, dtype=str, keep_default_na=False)
    if os.path.isfile(os.path.join(run_dir, "iterations.csv")):
        run = rep._run(run_dir)
        tols = sorted(set(SWEEP + (REPORT_LIKE_TOL,)) - {SUITE_TOL})
        rescored = pd.DataFrame({_rescored_column(t): rescored_iterations(
            run["steps"], run["iterations"], t) for t in tols})
        rescored.index.name = "step"
        rescored.to_csv(os.path.join(run_dir, "rescored.csv"))
    text[text["accepted"] == "true"][list(THIN_STEP_COLUMNS)].to_csv(steps_path, index=False)
    for name in os.listdir(run_dir):
        if name not in THIN_KEPT_FILES:
            path = os.path.join(run_dir, name)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)


def thin_records(results_dir):
    """thin_run on every run of the readings study's index."""
    index = _index(results_dir)
    for _, row in (index.iterrows() if index is not None else []):
        thin_run(os.path.join(results_dir, "readings", row["dir"]))


# --- the section -------------------------------------------------------------------------------

def _index(results_dir):
    path = os.path.join(results_dir, "readings", "index.csv")
    if not os.path.exists(path):
        return None
    return pd.read_csv(path, dtype={"settings": str}, keep_default_na=False)


def _records(results_dir, row):
    return rep._run(results_dir, "readings", row["dir"])


def _b_text(m):
    b = m["B"]
    if b is None:
        return "not reached"
    kind = "at a kink" if b["nonsmooth"] else "smooth"
    text = "%s, lambda %.3f, step %d" % (kind, b["lambda"], b["step"])
    return text + (" (%s)" % m["B_pair"] if m["B_pair"] else "")


def _path_text(m, row, full):
    text = "%d" % m["steps"]
    if int(row["exit_status"]) != 0:
        text += " (stopped, exit %s)" % row["exit_status"]
    elif m["steps"] < full:
        text += " (of %d)" % full
    return text


def _instability_text(m):
    i = m["instability_before_B"]
    if i is None:
        return "none"
    text = "%s at step %d" % (i["kind"].replace("_", " "), i["step"])
    if i["step"] == m["B"]["step"]:
        text += ", %.1e below B in lambda" % (m["B"]["lambda"] - i["lambda"])
    return text


def _runs(results_dir, index, problem, solver):
    """(index row, records) of the readings' runs of one problem and solver, in index order."""
    rows = index[(index["problem"] == problem) & (index["solver"] == solver) &
                 ~index["dir"].str.startswith("invariance")]
    for _, row in rows.iterrows():
        run = _records(results_dir, row)
        if run is not None and run["steps"] is not None:
            yield row, run


def _critical_points_table(results_dir, index, lines):
    lines += ["P2 (Newton): the limit point B, the bifurcation point C and the kinks. The report: "
              "B is a kink made by a contact change, C comes after it, 129 kinks on the path.",
              "", "| reading | settings | d / nc / members | steps | B | order of B, C | first "
              "instability before B | kinks before B / over the path |",
              "|---|---|---|---|---|---|---|---|"]
    measured = {}
    for row, run in _runs(results_dir, index, "arch-flat", "newton"):
        m = p2_measures(run)
        measured[row["reading"]] = m
        members = run["cells"]["cell"].nunique() if run["cells"] is not None else "?"
        lines.append("| %s | %s | %s / %s / %s | %s | %s | %s | %s | %s / %d |" % (
            row["reading"], row["settings"] or "(defaults)",
            rep._parameter(run, "num_dofs", "?"), rep._parameter(run, "num_pairs", "?"), members,
            _path_text(m, row, 2000), _b_text(m), m["order"], _instability_text(m),
            "-" if m["kinks_before_B"] is None else m["kinks_before_B"], m["kinks"]))
    lines.append("")
    return measured


def _table_1(results_dir, index, lines):
    lines += ["P2 against Table 1's statement (2 iterations at 273 steps, at most 4 at almost "
              "all), at the suite's stopping test and rescored at the report-like one:", "",
              "| reading | solver | steps | 2-iteration steps at %g / %g | share with <= 4 at "
              "%g / %g | most iterations at %g |" % (SUITE_TOL, REPORT_LIKE_TOL, SUITE_TOL,
                                                     REPORT_LIKE_TOL, SUITE_TOL),
              "|---|---|---|---|---|---|"]
    found = {}
    for solver in ("newton", "quasi-newton"):
        for row, run in _runs(results_dir, index, "arch-flat", solver):
            strict, loose = table_1_measures(run, SUITE_TOL), table_1_measures(run, REPORT_LIKE_TOL)
            found[(row["reading"], solver)] = (strict, loose)
            lines.append("| %s | %s | %s | %d / %d | %.1f%% / %.1f%% | %d |" % (
                row["reading"], solver, _path_text(strict, row, 2000), strict["two"],
                loose["two"], 100 * strict["at_most_4"], 100 * loose["at_most_4"], strict["max"]))
    lines.append("")
    return found


def _table_2(results_dir, index, lines):
    lines += ["P3 (quasi-Newton) against the report's Table 2, each histogram normalised by its "
              "own steps; the distance is the total variation 1/2 sum |p_k - q_k| (0: the same "
              "shape, 1: disjoint):", "",
              "| reading | steps | 3 / 4 / 5 iterations at %g (Table 2: 1081 / 379 / 100) | "
              "distance at %g | 2 / 3 / 4 / 5 at %g | distance at %g |" % (
                  SUITE_TOL, SUITE_TOL, REPORT_LIKE_TOL, REPORT_LIKE_TOL),
              "|---|---|---|---|---|---|"]
    distances = {}
    for row, run in _runs(results_dir, index, "arch-curved", "quasi-newton"):
        strict, loose = table_2_measures(run, SUITE_TOL), table_2_measures(run, REPORT_LIKE_TOL)
        distances[row["reading"]] = (strict["distance"], loose["distance"])
        hs, hl = strict["hist"], loose["hist"]
        lines.append("| %s | %s | %d / %d / %d | %.3f | %d / %d / %d / %d | %.3f |" % (
            row["reading"], _path_text({"steps": sum(hs.values())}, row, 1604), hs.get("3", 0),
            hs.get("4", 0), hs.get("5", 0), strict["distance"], hl.get("2", 0), hl.get("3", 0),
            hl.get("4", 0), hl.get("5", 0), loose["distance"]))
    lines.append("")
    return distances


# The stopping tests of the sweep: the suite's, then looser ones up to fsolve's usual 1e-6.
SWEEP = (1e-10, 3e-10, 1e-9, 3e-9, 1e-8, 1e-7, 1e-6)


def _sweep(results_dir, index, lines):
    """The default reading's counts over a range of stopping tests: {label: [values]}."""
    runs = {(p, s): run for p, s in (("arch-flat", "newton"), ("arch-flat", "quasi-newton"),
                                     ("arch-curved", "quasi-newton"))
            for row, run in _runs(results_dir, index, p, s) if row["reading"] == "default"}
    if not runs:
        return {}
    sweep = {}
    for (problem, solver), run in runs.items():
        if problem == "arch-flat":
            sweep["P2 %s: 2-iteration steps" % solver] = [
                table_1_measures(run, t)["two"] for t in SWEEP]
        else:
            sweep["P3 %s: distance to Table 2" % solver] = [
                "%.3f" % table_2_measures(run, t)["distance"] for t in SWEEP]
    lines += ["The default reading over a range of stopping tests ||F||_inf <= tol (rescored; the "
              "report: 273 two-iteration steps on P2, distance 0 to Table 2 on P3):", "",
              "| tol | " + " | ".join("%g" % t for t in SWEEP) + " |",
              "|---|" + "---|" * len(SWEEP)]
    for label, values in sweep.items():
        lines.append("| %s | " % label + " | ".join(str(v) for v in values) + " |")
    lines.append("")
    return sweep


def _invariance_table(results_dir, index, lines):
    rows = index[index["dir"].str.startswith("invariance")]
    default = index[(index["reading"] == "default") & (index["problem"] == "arch-flat") &
                    (index["solver"] == "newton")]
    found = {}
    if not len(rows):
        return found
    lines += ["The default P2 over the same 200 units of arc length at other arc lengths, and in "
              "the printed load unit (kN) with E = 20 MPa (the path depends only on load / EA):",
              "", "| run | settings | steps | kinks before B / over the path | B |",
              "|---|---|---|---|---|"]
    for _, row in pd.concat([default, rows]).iterrows():
        run = _records(results_dir, row)
        if run is None or run["steps"] is None:
            continue
        m = p2_measures(run)
        found[row["reading"]] = (m["kinks_before_B"], m["kinks"])
        lines.append("| %s | %s | %s | %s / %d | %s |" % (
            row["reading"], row["settings"] or "(defaults)", _path_text(m, row, m["steps"]),
            "-" if m["kinks_before_B"] is None else m["kinks_before_B"], m["kinks"], _b_text(m)))
    lines.append("")
    return found


def _small_multiples(fig, cell, runs, measured):
    """P2's paths, a panel per reading (11 overlaid lines could not be told apart): the
    reading's path in blue over all the others in grey, its point B marked (square: at a kink,
    circle: smooth); shared axes, labelled on the outer panels only."""
    paths = [(row["reading"], rep._accepted(run)) for row, run in runs]
    if not paths:
        return
    columns = 4 if len(paths) > 6 else min(3, len(paths))
    rows = -(-len(paths) // columns)
    grid = cell.subgridspec(rows, columns, hspace=0.5, wspace=0.08)
    first = None
    for k, (reading, acc) in enumerate(paths):
        ax = fig.add_subplot(grid[k // columns, k % columns], sharex=first, sharey=first)
        first = first or ax
        for _, other in paths:
            ax.plot(other["control_disp"], other["lambda"], color="0.82", lw=0.6)
        ax.plot(acc["control_disp"], acc["lambda"], color="tab:blue", lw=1.1)
        b = measured.get(reading, {}).get("B")
        if b is not None:
            ax.plot(b["control_disp"], b["lambda"], "s" if b["nonsmooth"] else "o",
                    color="tab:red", ms=5, mfc="none", mew=1.3)
        ax.set_title(reading, fontsize=7, pad=2)
        ax.tick_params(labelsize=6)
        ax.grid(True, alpha=0.3)
        if k % columns:
            ax.tick_params(labelleft=False)
        else:
            ax.set_ylabel("lambda [-]", fontsize=7)
        if k + columns < len(paths):
            ax.tick_params(labelbottom=False)
        else:
            ax.set_xlabel("u_x of node (a) [m]", fontsize=7)
    fig.text(0.06, 0.95, "P2 (Newton), a panel per reading: its path (blue) over the others "
             "(grey), B marked (square: at a kink, circle: smooth)", fontsize=9)


def _figure(results_dir, index, measured, distances, sweep):
    """P2's path of each reading in a small panel of its own (the others in grey behind it, B
    marked), P3's distance to Table 2 per reading at both stopping tests, and the default's
    2-iteration steps over the stopping tests of the sweep."""
    fig = plt.figure(figsize=(18, 7))
    outer = fig.add_gridspec(1, 3, width_ratios=[3.4, 2, 2], wspace=0.3)
    _small_multiples(fig, outer[0], list(_runs(results_dir, index, "arch-flat", "newton")),
                     measured)
    table_2, table_1 = fig.add_subplot(outer[1]), fig.add_subplot(outer[2])
    names = list(distances)
    xs = np.arange(len(names))
    table_2.bar(xs - 0.2, [distances[r][0] for r in names], 0.4,
                label="stopping test %g" % SUITE_TOL)
    table_2.bar(xs + 0.2, [distances[r][1] for r in names], 0.4,
                label="rescored at %g" % REPORT_LIKE_TOL)
    table_2.set_xticks(xs)
    table_2.set_xticklabels(names, rotation=45, ha="right", fontsize=8)
    table_2.set_ylabel("distance to Table 2 (total variation)")
    table_2.set_title("P3 (quasi-Newton) against the report's Table 2", fontsize=9)
    table_2.grid(True, axis="y", alpha=0.3)
    table_2.legend(fontsize=8)
    for label, values in sweep.items():
        if label.startswith("P2"):
            table_1.semilogx(SWEEP, values, "o-", label=label.split(":")[0])
    table_1.axhline(REPORT_TABLE_1["two_iterations"], color="k", ls="--", lw=1,
                    label="the report (273)")
    table_1.set_xlabel("stopping test ||F||_inf <= tol")
    table_1.set_ylabel("P2 steps with 2 iterations")
    table_1.set_title("P2, default reading: Table 1's count against the stopping test",
                      fontsize=9)
    table_1.grid(True, which="both", alpha=0.3)
    table_1.legend(fontsize=8)
    return rep._save(fig, results_dir, "readings.png")


def _names(readings):
    return ", ".join(readings) if readings else "none"


def what_the_readings_show(measured, invariance, table_1, distances):
    """The findings of the study, from its measures: which readings give the report's B and C,
    the kinks and their invariances, and the two tables against the stopping test."""
    out = ["What the readings show:", ""]
    if measured:
        angular = [r for r, m in measured.items() if m["B"] is not None and m["B"]["nonsmooth"]]
        b_first = [r for r, m in measured.items() if m["order"].startswith("B before C")]
        clean = [r for r in angular if r in b_first and measured[r]["instability_before_B"] is None]
        out.append("- B at a kink (a contact change, as in the report): %s. B before C (the "
                   "report's order): %s. Both, with no instability before B: %s." % (
                       _names(angular), _names(b_first), _names(clean)))
        for r in angular:
            m = measured[r]
            before = m["instability_before_B"]
            first = "; first a %s" % _instability_text(m) if before is not None else ""
            out.append("  - %s: B at lambda %.3f%s%s%s." % (
                r, m["B"]["lambda"], " (%s)" % m["B_pair"] if m["B_pair"] else "", first,
                "; the path stops after %d steps" % m["steps"] if m["steps"] < 2000 else ""))
        default = measured.get("default")
        if default is not None and default["B"] is not None:
            out.append("- The default reading: B %s, %s." % (
                "at a kink" if default["B"]["nonsmooth"] else "smooth", default["order"]))
        most = max(measured.items(), key=lambda item: item[1]["kinks"])
        out.append("- Kinks over the traced path: %d to %d (most: %s); the report locates %d.%s"
                   % (min(m["kinks"] for m in measured.values()), most[1]["kinks"], most[0],
                      rep.REPORT_P2["kinks"],
                      " No reading comes near it." if 2 * most[1]["kinks"] < rep.REPORT_P2["kinks"]
                      else ""))
    if invariance:
        counts = sorted(set(invariance.values()), key=str)
        out.append("- Kinks before B / over the path in the invariance table: %s: %s." % (
            " or ".join("%s / %d" % c for c in counts),
            "the same at every arc length and in either load unit" if len(counts) == 1
            else "they depend on the arc length or the load unit"))
    newton, qn = table_1.get(("default", "newton")), table_1.get(("default", "quasi-newton"))
    if newton and qn:
        out.append("- Table 1 (2 iterations at 273 steps): the default P2 has %d two-iteration "
                   "steps with Newton at the suite's stopping test %g, %d with quasi-Newton; "
                   "rescored at %g, %d and %d. The count is a property of the solver and the "
                   "stopping test more than of the truss." % (
                       newton[0]["two"], SUITE_TOL, qn[0]["two"], REPORT_LIKE_TOL,
                       newton[1]["two"], qn[1]["two"]))
    if "default" in distances:
        strict, loose = distances["default"]
        best = min(distances.items(), key=lambda item: item[1][0])
        out.append("- Table 2: the default P3 is %.3f from the report's histogram at %g (the "
                   "closest reading: %s, %.3f) and %.3f at %g: one stopping test does not fit "
                   "both tables." % (strict, SUITE_TOL, best[0], best[1][0], loose,
                                     REPORT_LIKE_TOL))
    out.append("")
    return out


def section(results_dir):
    """The REPORT.md section of the readings study, or None when its records are absent."""
    index = _index(results_dir)
    if index is None or not len(index):
        return None
    lines = ["## Readings of the report's figure", "",
             "The report's figure of P2 and P3 is not legible enough to read the truss, so its "
             "topology, member groups and lower-node placement are readings (docs/problems.md, "
             "\"Other readings\"). Each reading below is a set of problem parameters; P2 is "
             "traced with Newton (2000 steps, critical points located), P3 with quasi-Newton "
             "(1604 steps). Made by `%s`. Iteration counts are also rescored at a report-like "
             "stopping test ||F||_inf <= %g instead of the suite's %g: the first recorded "
             "iteration of each accepted step that meets it (iterations.csv)."
             % (COMMAND, REPORT_LIKE_TOL, SUITE_TOL), ""]
    measured = _critical_points_table(results_dir, index, lines)
    invariance = _invariance_table(results_dir, index, lines)
    table_1 = _table_1(results_dir, index, lines)
    distances = _table_2(results_dir, index, lines)
    sweep = _sweep(results_dir, index, lines)
    if measured or distances:
        path = _figure(results_dir, index, measured, distances, sweep)
        lines += ["![Readings of P2 and P3](%s)" % path, ""]
    lines += what_the_readings_show(measured, invariance, table_1, distances)
    return lines
