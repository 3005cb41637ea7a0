"""The reproduction of the report's three examples: RESULTS_DIR/REPORT.md and its figures.

`write(results_dir)` reads only the records of `contactbench run` under
  results_dir/block/<eta case>-<solver>/     P1 (report 5.1), the fixed-load solve
  results_dir/arch-flat/<solver>/            P2 (report 5.2), the arc-length path
  results_dir/arch-curved/<solver>/          P3 (report 5.3), the arc-length path
(steps.csv, iterations.csv, kinks.csv, critical.csv, snapshots.csv, snapshot_contacts.csv,
cells.csv, parameters.csv: docs/records.md) and writes results_dir/REPORT.md and PNG figures
into results_dir/figures/reproduction/. Every published number of the report is set beside the
suite's own; where they disagree the report says so.
"""
import json
import math
import os

import numpy as np
import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.collections import LineCollection  # noqa: E402

from plotlib import histograms, obstacles, quick  # noqa: E402

FIGURES = os.path.join("figures", "reproduction")
ETA_LABEL = {1: "case 1 (proposed)", 2: "case 2", 3: "case 3 (degenerate)",
             4: "case 4 (nonsmooth FB)"}
SOLVER_LABEL = {"dogleg": "trust-region dogleg", "newton": "Newton (line search)",
                "quasi-newton": "quasi-Newton (Broyden)"}
# The report's published figures (METR 2009-06, section 5; docs/problems.md).
REPORT_P1_CASE1_TIME_S = 50.4  # MATLAB fsolve, Core2 Duo 2.26 GHz
REPORT_TABLE_2 = {3: 1081, 4: 379, 5: 100, 6: 6, 7: 7, 8: 10, 9: 9, 10: 10, 12: 2}
REPORT_P2 = {"d": 119, "nc": 90, "kinks": 129}
REPORT_P3 = {"d": 279, "nc": 210, "steps": 1604}
# Below this residual norm the history is at the rounding floor of (29) and tells no rate.
RATE_FLOOR = 1e-11
# The deformed mesh is red in the deformed-shape figures, so the obstacles are drawn in blue.
OBSTACLE_COLOUR = "tab:blue"


def _read(path):
    return pd.read_csv(path) if os.path.exists(path) and os.path.getsize(path) > 0 else None


def _run(results_dir, *parts):
    """The records of one run directory, or None when it is missing."""
    d = os.path.join(results_dir, *parts)
    if not os.path.isdir(d):
        return None
    files = ["steps", "iterations", "kinks", "critical", "snapshots", "snapshot_contacts",
             "cells", "parameters", "rescored"]
    run = {f: _read(os.path.join(d, f + ".csv")) for f in files} | {"dir": d}
    path = os.path.join(d, "parameters.csv")
    if os.path.exists(path):  # values as written ("50", not 50.0)
        run["parameters"] = pd.read_csv(path, dtype=str, keep_default_na=False)
    return run


def _parameter(run, name, default=None):
    p = run["parameters"]
    if p is None:
        return default
    row = p[p["name"] == name]
    return row["value"].iloc[0] if len(row) else default


def _save(fig, results_dir, name):
    os.makedirs(os.path.join(results_dir, FIGURES), exist_ok=True)
    path = os.path.join(FIGURES, name)
    fig.savefig(os.path.join(results_dir, path), dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


# --- P1: residual histories and rates --------------------------------------------------------

def convergence_rates(residuals):
    """Rates of a residual-norm history e_k: the last ratio e_{k+1}/e_k and the last order
    estimate log(e_{k+1}/e_k) / log(e_k/e_{k-1}), both over iterates above RATE_FLOOR.
    Returns (ratio, order) with nan where the history is too short."""
    e = np.asarray([x for x in residuals if x > RATE_FLOOR], dtype=float)
    ratio = order = float("nan")
    if e.size >= 2:
        ratio = e[-1] / e[-2]
    if e.size >= 3 and e[-2] != e[-3] and e[-1] > 0:
        order = math.log(e[-1] / e[-2]) / math.log(e[-2] / e[-3])
    return ratio, order


def classify(ratio, order, iterations, converged):
    if not converged:
        return "did not converge"
    if math.isnan(ratio):
        return "converged (too few iterations to tell)"
    if order > 1.4 or ratio < 0.05:
        return "superlinear at the end"
    if ratio > 0.2:
        return "linear at the end (ratio %.2f)" % ratio
    return "fast linear (ratio %.2f)" % ratio


def _load_at_start(run):
    """The 1-minute load average at the start of a run (run.json), or None."""
    try:
        with open(os.path.join(run["dir"], "run.json")) as f:
            return json.load(f)["load_average"]["start"]["1min"]
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _p1_timing(results_dir, run):
    """What the table's times are: one solve each, the load, and the same solve repeated in the
    comparison set block (median and range), when that set is there."""
    load = _load_at_start(run)
    text = "Times: one solve each (the iteration counts are the result; a time is one sample), " \
        "load average (1 min) %s at the start." % ("%.2f" % load if load is not None
                                                   else "not recorded")
    steps = _read(os.path.join(results_dir, "compare", "block", "steps.csv"))
    if steps is None or "time_min_s" not in steps:
        return text
    rows = steps[(steps["formulation"] == "implicit-fb") & (steps["start"] == "cold")]
    if not len(rows):
        return text
    r = rows.iloc[-1]
    return text + (" Their spread: the Newton solve of case 1, repeated %d times in the comparison "
                   "set `block` (COMPARISON.md), took %.3g s (median; fastest %.3g s, slowest "
                   "%.3g s)." % (r["time_samples"], r["time_s"], r["time_min_s"],
                                 r["time_max_s"]))


def p1(results_dir, lines):
    runs = {}
    for solver in ("dogleg", "newton"):
        for case in ("1", "2", "3", "4", "3-near"):
            r = _run(results_dir, "block", "eta%s-%s" % (case, solver))
            if r is not None and r["steps"] is not None:
                runs[(solver, case)] = r
    if not runs:
        lines += ["## P1 `block` (report 5.1)", "", "No records in results/block/.", ""]
        return
    lines += ["## P1 `block`: small deformation, cold start (report 5.1)", ""]
    any_run = next(iter(runs.values()))
    lines.append("d = %s, nc = %s (the report: d = 5202, nc = 102). One fixed-load solve from "
                 "u0 = 0, g0 = -1, r0 = +1 (scaled)." % (_parameter(any_run, "num_dofs", "?"),
                                                         _parameter(any_run, "num_pairs", "?")))
    lines.append("")
    table = ["| solver | eta case | start | iterations | time [s], one solve | verified | "
             "last ratio e_k+1/e_k | order estimate | behaviour at the end |",
             "|---|---|---|---|---|---|---|---|---|"]
    behaviour = {}
    for solver in ("dogleg", "newton"):
        fig, ax = plt.subplots(figsize=(7.5, 4.8))
        for case in ("1", "2", "3", "4", "3-near"):
            r = runs.get((solver, case))
            if r is None:
                continue
            step = r["steps"].iloc[-1]
            it = r["iterations"]
            merit = it["merit"].to_numpy() if it is not None else np.array([])
            sumsq = 2.0 * merit  # sum of squares of the scaled residual of (29)-(32)
            eta = int(case[0])
            label = ETA_LABEL[eta] + (", near the solution" if case.endswith("near") else "")
            style = "--" if case.endswith("near") else "-"
            if sumsq.size:
                ax.semilogy(it["iteration"], np.maximum(sumsq, 1e-32), style, label=label, lw=1.4)
            ratio, order = convergence_rates(np.sqrt(np.maximum(sumsq, 0.0)))
            verified = bool(step["verified"])
            kind = classify(ratio, order, int(step["iterations"]), verified)
            behaviour[(solver, case)] = (int(step["iterations"]), verified, kind, ratio)
            table.append("| %s | %s | %s | %d | %.3g | %s | %.3g | %.2f | %s |" % (
                solver, eta, "near" if case.endswith("near") else "cold", step["iterations"],
                step["time_s"], "yes" if verified else "no", ratio, order, kind))
        ax.set_xlabel("iteration")
        ax.set_ylabel("sum of squares of the residual (scaled system)")
        ax.set_title("P1 block, implicit-fb, %s: residual history (cf. the report's Figure 4)"
                     % SOLVER_LABEL[solver], fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        path = _save(fig, results_dir, "p1_residuals_%s.png" % solver)
        lines.append("![P1 residual history, %s](%s)" % (solver, path))
        lines.append("")
    lines += table + [""]
    lines.append(_p1_timing(results_dir, any_run))
    lines.append("")
    lines.append("Rates are estimated from the recorded histories (iterations.csv): e_k = "
                 "sqrt(2 merit_k), over the iterates above %g (below it the residual is at the "
                 "rounding floor); the order estimate is log(e_k+1/e_k) / log(e_k/e_k-1) of the "
                 "last three." % RATE_FLOOR)
    lines.append("")
    lines.append("What the report claims, and what the records show (dogleg, the report's solver):")
    lines.append("")
    d = {c: behaviour.get(("dogleg", c)) for c in ("1", "2", "3", "4", "3-near")}
    if d["1"] and d["2"]:
        lines.append("- Cases 1 and 2 converge fast at the end: %s (case 1: %s, %d iterations; "
                     "case 2: %s, %d iterations)." % (
                         "agrees" if all("superlinear" in d[c][2] for c in ("1", "2"))
                         else "partly: see the table", d["1"][2], d["1"][0], d["2"][2], d["2"][0]))
    if d["3"]:
        lines.append("- Case 3 converges only linearly and fails within 1000 iterations from the "
                     "cold start: from the cold start the suite's case 3 %s in %d iterations "
                     "(%s)%s." % (
                         "converges" if d["3"][1] else "does not converge", d["3"][0], d["3"][2],
                         " -- this DISAGREES with the report" if d["3"][1] else ""))
    if d["3-near"]:
        lines.append("- Case 3 from a start near the solution: %s, %d iterations, %s." % (
            "converged" if d["3-near"][1] else "not converged", d["3-near"][0], d["3-near"][2]))
    if d["4"] and d["1"]:
        lines.append("- Case 4 (nonsmooth FB) needs far more iterations than cases 1 and 2: %d "
                     "against %d and %d (%s)." % (
                         d["4"][0], d["1"][0], d["2"][0] if d["2"] else -1,
                         "agrees" if d["4"][0] > 2 * max(d["1"][0], d["2"][0] if d["2"] else 0)
                         else "DISAGREES: not far more"))
    if d["1"]:
        lines.append("- CPU time of case 1: the report 50.4 s (MATLAB fsolve, Core2 Duo 2.26 GHz); "
                     "the suite %.3g s (C++, dogleg, one solve on this machine; the timing above "
                     "gives the spread; see results/COMPARISON.md for the machine)."
                     % runs[("dogleg", "1")]["steps"].iloc[-1]["time_s"])
    lines.append("")
    # The deformed configuration (report Figure 3), from case 1 with Newton.
    r = runs.get(("newton", "1")) or runs.get(("dogleg", "1"))
    if r is not None and r["snapshots"] is not None and r["cells"] is not None:
        snap = r["snapshots"]
        snap = snap[snap["label"] == "final"]
        u = np.hypot(snap["ux"], snap["uy"]).max()
        width = snap["x"].max() - snap["x"].min()
        amplification = 0.1 * width / u if u > 0 else 1.0
        fig, ax = plt.subplots(figsize=(6, 6))
        _draw_mesh(ax, snap, r["cells"], 0.0, color="0.8", lw=0.4)
        _draw_mesh(ax, snap, r["cells"], amplification, color="C0", lw=0.4)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title("P1 block, implicit-fb: deformed configuration (displacements x %.0f), "
                     "undeformed in grey (cf. the report's Figure 3)" % amplification, fontsize=9)
        path = _save(fig, results_dir, "p1_deformed.png")
        lines += ["![P1 deformed configuration](%s)" % path, ""]


def _draw_mesh(ax, snap, cells, amplification, **style):
    xy = snap.set_index("node")[["x", "y", "ux", "uy"]]
    pos = xy[["x", "y"]].to_numpy() + amplification * xy[["ux", "uy"]].to_numpy()
    index = {n: i for i, n in enumerate(xy.index)}
    segments = []
    for _, cell in cells.groupby("cell"):
        nodes = [index[n] for n in cell.sort_values("corner")["node"]]
        ring = nodes + [nodes[0]] if len(nodes) > 2 else nodes
        for a, b in zip(ring[:-1], ring[1:]):
            segments.append([pos[a], pos[b]])
    ax.add_collection(LineCollection(segments, **style))
    ax.autoscale_view()


# --- P2 and P3: paths, critical points, histograms --------------------------------------------

def _accepted(run):
    s = run["steps"]
    return s[s["accepted"] == 1] if s is not None else None


# Histogram columns: 1 ... 12 as the report's tables, then ranges (long tails of hard steps).
HISTOGRAM_BINS = [(c, c) for c in range(1, 13)] + [(13, 20), (21, 50), (51, None)]


def _bin_label(lo, hi):
    return str(lo) if lo == hi else ("%d-%d" % (lo, hi) if hi else "> %d" % (lo - 1))


def _histogram(accepted):
    it = accepted["iterations"]
    return pd.Series({_bin_label(lo, hi): int(((it >= lo) & ((it <= hi) if hi else True)).sum())
                      for lo, hi in HISTOGRAM_BINS})


def _histogram_table(hists, report=None, report_label="the report"):
    counts = [_bin_label(lo, hi) for lo, hi in HISTOGRAM_BINS]
    used = [c for c in counts if any(h.get(c, 0) for h in hists.values()) or
            (report and report.get(c, 0))]
    counts = used
    out = ["| iterations | " + " | ".join(str(c) for c in counts) + " | steps |",
           "|---|" + "---|" * (len(counts) + 1)]
    if report:
        out.append("| %s | " % report_label + " | ".join(str(report.get(c, 0)) for c in counts) +
                   " | %d |" % sum(report.values()))
    for name, h in hists.items():
        out.append("| %s | " % name + " | ".join(str(int(h.get(c, 0))) for c in counts) +
                   " | %d |" % int(h.sum()))
    return out


POINT_COLOUR = {"B": "tab:red", "C": "tab:purple", "D": "tab:green"}


def _draw_path(ax, run, labels, **point_style):
    """The accepted states per branch, the located kinks and the labelled points."""
    acc = _accepted(run)
    for branch, part in acc.groupby("branch"):
        ax.plot(part["control_disp"], part["lambda"], "-", lw=1.2,
                label="branch %d%s" % (branch, " (after the switch)" if branch else ""))
    k = run["kinks"]
    if k is not None and len(k):
        k = k[(k["verified"] == 1) & (k["between"] == 1)]
        ax.plot(k["control_disp"], k["lambda"], "k.", ms=4, label="kinks (%d)" % len(k))
    for key, (row, style) in labels.items():
        if row is not None:
            ax.plot(row["control_disp"], row["lambda"], style, mfc="none",
                    color=POINT_COLOUR.get(key, "k"), gid=key,
                    label="%s: lambda = %.9g" % (key, row["lambda"]), **point_style)


def inset_window(points, x_range, y_range, margin=1.5, floor=1e-12):
    """((x0, x1), (y0, y1)) around `points` ((x, y) pairs): centred on them, its half sizes
    `margin` times their largest separation, measured in fractions of the main axes' data
    ranges so that the inset keeps the main figure's proportions; at least `floor` of those
    ranges, so that coinciding points still give a window."""
    xy = np.asarray(points, dtype=float)
    centre = (xy.max(axis=0) + xy.min(axis=0)) / 2
    ranges = np.array([x_range, y_range], dtype=float)
    ranges[ranges <= 0] = 1.0
    spread = ((xy.max(axis=0) - xy.min(axis=0)) / ranges).max()
    half = margin * max(spread, floor) * ranges
    return tuple((c - h, c + h) for c, h in zip(centre, half))


def _zoom_inset(ax, run, labels, keys):
    """An inset of the main axes around the points `keys` of `labels`, the path and the points
    drawn again at that scale (B and C of P2 lie a hair apart)."""
    rows = [labels[k][0] for k in keys if labels.get(k, (None,))[0] is not None]
    if len(rows) < 2:
        return None
    acc = _accepted(run)
    window = inset_window([(r["control_disp"], r["lambda"]) for r in rows],
                          np.ptp(acc["control_disp"]), np.ptp(acc["lambda"]))
    inset = ax.inset_axes([0.56, 0.08, 0.4, 0.42])
    _draw_path(inset, run, {k: labels[k] for k in keys}, ms=9, mew=1.6)
    inset.set_xlim(*window[0])
    inset.set_ylim(*window[1])
    inset.tick_params(labelsize=7)
    inset.set_title("around " + " and ".join(keys), fontsize=8)
    inset.grid(True, alpha=0.3)
    ax.indicate_inset_zoom(inset, edgecolor="0.4")
    return inset


def _path_figure(results_dir, run, title, name, labels, inset=()):
    """The path with its kinks and the points of `labels` ({key: (row, marker)}); `inset`: the
    keys of points to show again in a zoomed inset."""
    fig, ax = plt.subplots(figsize=(8, 5))
    _draw_path(ax, run, labels, ms=10, mew=1.8)
    for i, (key, (row, style)) in enumerate(labels.items()):
        if row is not None:
            # Staggered offsets: points close together keep their letters apart.
            ax.annotate(key, (row["control_disp"], row["lambda"]), textcoords="offset points",
                        xytext=(-22 + 16 * i, -22 + 12 * i), fontsize=12, fontweight="bold")
    _zoom_inset(ax, run, labels, inset)
    ax.set_xlabel("x-displacement of node (a) [m]")
    ax.set_ylabel("load parameter lambda [-]")
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    return _save(fig, results_dir, name)


def _deformed_figure(results_dir, run, label, title, name):
    snap, cells = run["snapshots"], run["cells"]
    if snap is None or cells is None:
        return None
    snap = snap[snap["label"] == label]
    if not len(snap):
        return None
    snap = snap[snap["step"] == snap["step"].max()]
    fig, ax = plt.subplots(figsize=(10, 3.6))
    _draw_mesh(ax, snap, cells, 0.0, color="0.75", lw=0.6)
    _draw_mesh(ax, snap, cells, 1.0, color="C3", lw=0.9)
    drawn = obstacles.read(run["dir"])
    if drawn:
        _draw_obstacles_around_mesh(ax, drawn)
        title += ", the obstacles in blue"
    else:
        title += " (the records hold no obstacle geometry: vtk/*obstacle*.vtp)"
    contacts = run["snapshot_contacts"]
    if contacts is not None:
        c = contacts[(contacts["label"] == label) & (contacts["step"] == snap["step"].iloc[0])]
        closed = c[c["r"] < 0]["node"].unique()
        xy = snap.set_index("node")
        ax.plot(xy.loc[closed, "x"] + xy.loc[closed, "ux"],
                xy.loc[closed, "y"] + xy.loc[closed, "uy"],
                "ko", ms=4, mfc="none", label="nodes in contact")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="upper right")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title, fontsize=10)
    return _save(fig, results_dir, name)


def _draw_obstacles_around_mesh(ax, drawn, margin=0.15):
    """The obstacles, seen through a window around the mesh (its extent and `margin` of its
    larger side each way): an obstacle's geometry may reach far beyond the body (a half-plane's
    line, a large disc) and would otherwise shrink the mesh to a speck."""
    box = ax.dataLim.frozen()  # a copy: drawing the obstacles grows ax.dataLim itself
    pad = margin * max(box.width, box.height)
    obstacles.draw(ax, drawn, colour=OBSTACLE_COLOUR)
    ax.set_xlim(box.x0 - pad, box.x1 + pad)
    ax.set_ylim(box.y0 - pad, box.y1 + pad)


def _critical(run, kind, switched=None):
    c = run["critical"]
    if c is None or not len(c):
        return c.iloc[0:0] if c is not None else None
    c = c[c["kind"] == kind]
    if switched is not None:
        c = c[c["switched"] == (1 if switched else 0)]
    return c


def _reconstruction(run, lines):
    p = run["parameters"]
    if p is None:
        return
    lines += ["| parameter | value | meaning |", "|---|---|---|"]
    for _, row in p.iterrows():
        meaning = str(row["doc"]).replace("|", "/")
        lines.append("| %s | %s | %s |" % (row["name"], row["value"], meaning))
    lines.append("")


def _path_runs(results_dir, problem, heading, lines):
    """The Newton and quasi-Newton runs of an arc-length problem, the one the tables describe
    (Newton when present), and its located kinks; None when there are no records."""
    runs = {s: _run(results_dir, problem, s) for s in ("newton", "quasi-newton")}
    runs = {s: r for s, r in runs.items() if r is not None and r["steps"] is not None}
    lines += [heading, ""]
    if not runs:
        lines += ["No records in results/%s/." % problem, ""]
        return None
    r = runs.get("newton") or next(iter(runs.values()))
    k = r["kinks"]
    kinks = int(((k["verified"] == 1) & (k["between"] == 1)).sum()) if k is not None else 0
    return runs, r, kinks


def branch_switch(run, c):
    """What the records say of the switch at the bifurcation point c (a critical.csv row or
    None): (switched, the first accepted step that left c onto another branch or None, the
    message critical.csv gives c). Switched only when critical.csv marks c switched and an
    accepted step records the switch."""
    acc = _accepted(run)
    left = acc[acc["branch_switch"] == 1] if acc is not None and len(acc) else None
    step = left.iloc[0] if left is not None and len(left) else None
    if c is None:
        return False, step, ""
    return bool(c["switched"]) and step is not None, step, str(c["message"])


def _d_cell(d, switched):
    """The suite's cell of the row "D, on the asymmetric branch": the last state when the path
    switched onto another branch and ends on it, else why D is not reached."""
    where = "lambda = %.4f, u_a = %.4f m" % (d["lambda"], d["control_disp"])
    if switched and int(d["branch"]) != 0:
        return "%s (the last state, branch %d, after the switch at C)" % (where, d["branch"])
    if switched:
        return "not reached: the path switched at C but ends back on branch 0 (%s)" % where
    return ("not reached: no branch switch, the path ends on branch %d, the branch through B "
            "and C (the last state: %s)" % (d["branch"], where))


def _switch_sentence(c, switched, d, message):
    if c is None:
        return "No bifurcation point was located on the path, so no branch was switched onto."
    if switched and d is not None and int(d["branch"]) != 0:
        return ("At C the path switched onto branch %d and ends on it, at D." % d["branch"])
    if switched:
        return "At C the path switched branch, but it ends on branch 0."
    return ("At C the branch switch did not happen (%s), so the path ends on branch 0 and D, "
            "the report's state on the asymmetric branch, is not reached." % message)


def p2(results_dir, lines):
    found = _path_runs(results_dir, "arch-flat",
                       "## P2 `arch-flat`: large deformation, two flat obstacles (report 5.2)",
                       lines)
    if found is None:
        return
    runs, r, kinks = found
    acc = _accepted(r)
    limits = _critical(r, "limit")
    bif = _critical(r, "bifurcation")
    switched_rows = bif[bif["switched"] == 1] if bif is not None else None
    b = limits.iloc[0] if limits is not None and len(limits) else None
    c = switched_rows.iloc[0] if switched_rows is not None and len(switched_rows) else (
        bif.iloc[0] if bif is not None and len(bif) else None)
    last = acc.iloc[-1] if acc is not None and len(acc) else None
    switched, _, message = branch_switch(r, c)
    at_d = switched and last is not None and int(last["branch"]) != 0
    lines += ["| quantity | the report | the suite (Newton) |", "|---|---|---|",
              "| d | %d | %s |" % (REPORT_P2["d"], _parameter(r, "num_dofs", "?")),
              "| nc | %d | %s |" % (REPORT_P2["nc"], _parameter(r, "num_pairs", "?")),
              "| steps traced (arc length %s) | not stated | %d |" % (
                  _parameter(r, "arc_length", "?"), len(acc)),
              "| kinks located on the path | 129 | %d |" % kinks]
    if b is not None:
        lines.append("| B, limit point | a kink (contact change) | "
                     "lambda = %.4f, u_a = %.4f m, %s, step %d |" % (
                         b["lambda"], b["control_disp"],
                         "at a kink" if b["nonsmooth"] else "smooth (no kink)", b["step"]))
    if c is not None:
        lines.append("| C, bifurcation point | after B | "
                     "lambda = %.6f, u_a = %.4f m, step %d, %s |" % (
                         c["lambda"], c["control_disp"], c["step"],
                         "branch switched" if switched else "not switched"))
    if last is not None:
        lines.append("| D, on the asymmetric branch | beyond C | %s |" % _d_cell(last, switched))
    lines.append("")
    if b is not None and c is not None:
        c_first = (c["step"], c["lambda"]) < (b["step"], b["lambda"])
        lines.append("The suite's B is %s; C lies a hair %s B (%.1e apart in lambda; "
                     "docs/findings.md says why). The report's B is a kink made by "
                     "a contact change with C after it, and it locates %d kinks against the "
                     "suite's %d. Whether another reading of the report's figure gives that, and "
                     "how the kinks and Table 1's counts depend on the arc length, the load unit "
                     "and the stopping test, is measured in \"Readings of the report's figure\" "
                     "(when its records exist; `bash scripts/run_readings.sh`)." % (
                         "at a kink" if b["nonsmooth"] else "a smooth limit point (no contact "
                         "change within a step of it)", "before" if c_first else "past",
                         abs(c["lambda"] - b["lambda"]), REPORT_P2["kinks"], kinks))
        lines.append("")
    lines += [_switch_sentence(c, switched, last, message), ""]
    # The last state is D only when the path switched and ends on the other branch.
    end_key = "D" if at_d else "end"
    labels = {"B": (b, "s"), "C": (c, "D"), end_key: (last, "o")}
    shown = [what for what, row in (("limit point B", b), ("bifurcation point C", c)) if
             row is not None]
    shown.append("the state D on branch %d after the switch" % last["branch"] if at_d else
                 "the last state, on branch %d (D not reached: %s)" % (
                     last["branch"], "no switch" if not switched else "back on branch 0")
                 if last is not None else "no state")
    path = _path_figure(results_dir, r, "P2 arch-flat, implicit-fb, Newton: equilibrium path "
                        "with kinks, %s" % ", ".join(shown), "p2_path.png", labels,
                        inset=("B", "C"))
    lines += ["![P2 path](%s)" % path, ""]
    where = ("D (branch %d)" % last["branch"] if at_d else
             "the last state (branch %d; D not reached)" % last["branch"]) \
        if last is not None else ""
    path = _deformed_figure(results_dir, r, "final", "P2 arch-flat, implicit-fb, Newton: "
                            "deformed configuration at %s (red) over the undeformed (grey)" % where,
                            "p2_deformed_last.png")
    if path:
        lines += ["![P2 deformed at %s](%s)" % ("D" if at_d else "the last state", path), ""]
    lines += ["Iterations per accepted step (the form of the report's Table 1; the report: 2 "
              "iterations at 273 steps, at most 4 at almost all steps):", ""]
    lines += _histogram_table({SOLVER_LABEL[s]: _histogram(_accepted(x)) for s, x in runs.items()})
    lines.append("")
    for s, x in runs.items():
        bx = _critical(x, "bifurcation")
        if bx is not None and len(bx) and not (bx["switched"] == 1).any():
            lines.append("- %s: the bifurcation point was located but not left: %s" % (
                SOLVER_LABEL[s], bx["message"].iloc[-1]))
        elif bx is not None and len(bx) and len(bx[bx["switched"] == 0]):
            lines.append("- %s: %s" % (SOLVER_LABEL[s],
                                       bx[bx["switched"] == 0]["message"].iloc[-1]))
    lines.append("")


def p3(results_dir, lines):
    found = _path_runs(results_dir, "arch-curved",
                       "## P3 `arch-curved`: flat and curved obstacles (report 5.3)", lines)
    if found is None:
        return
    runs, r, kinks = found
    acc = _accepted(r)
    limits = _critical(r, "limit")
    nonsmooth = limits[limits["nonsmooth"] == 1] if limits is not None else None
    b = nonsmooth.iloc[0] if nonsmooth is not None and len(nonsmooth) else None
    c = acc.iloc[-1]
    lines += ["| quantity | the report | the suite (Newton) |", "|---|---|---|",
              "| d | %d | %s |" % (REPORT_P3["d"], _parameter(r, "num_dofs", "?")),
              "| nc | %d | %s |" % (REPORT_P3["nc"], _parameter(r, "num_pairs", "?")),
              "| steps (arc length 0.1) | 1604 | %d |" % len(acc),
              "| kinks located | not stated | %d |" % kinks,
              "| limit points (lambda turns) | B, nonsmooth | %d, of which %d at a kink |" % (
                  len(limits) if limits is not None else 0,
                  len(nonsmooth) if nonsmooth is not None else 0)]
    if b is not None:
        lines.append("| B, first nonsmooth limit point | passed | "
                     "lambda = %.4f, u_a = %.4f m, step %d |" % (
                         b["lambda"], b["control_disp"], b["step"]))
    lines.append("| C, the end of the traced path | after 1604 steps | "
                 "lambda = %.4f, u_a = %.4f m |" % (c["lambda"], c["control_disp"]))
    lines.append("")
    path = _path_figure(results_dir, r, "P3 arch-curved, implicit-fb, Newton: equilibrium path "
                        "with kinks, %send point C" % (
                            "nonsmooth limit point B and " if b is not None else
                            "no nonsmooth limit point, "), "p3_path.png",
                        {"B": (b, "s"), "C": (c, "o")})
    lines += ["![P3 path](%s)" % path, ""]
    path = _deformed_figure(results_dir, r, "final", "P3 arch-curved, implicit-fb, Newton: "
                            "deformed configuration at C (red) over the undeformed (grey)",
                            "p3_deformed_C.png")
    if path:
        lines += ["![P3 deformed at C](%s)" % path, ""]
    lines += ["Iterations per accepted step beside the report's Table 2 (BFGS quasi-Newton "
              "csolve, 1604 steps):", ""]
    hists = {SOLVER_LABEL[s]: _histogram(_accepted(x)) for s, x in runs.items()}
    report_binned = {str(k): v for k, v in REPORT_TABLE_2.items()}
    lines += _histogram_table(hists, report_binned, "the report (csolve)")
    lines.append("")
    fig, ax = plt.subplots(figsize=(8, 4.5))
    counts = [_bin_label(lo, hi) for lo, hi in HISTOGRAM_BINS]
    width = 0.8 / (len(hists) + 1)
    xs = np.arange(len(counts))
    bars = [("the report (csolve)", [report_binned.get(c, 0) for c in counts])]
    bars += [("suite: " + name, [h.get(c, 0) for c in counts]) for name, h in hists.items()]
    for i, (name, heights) in enumerate(bars):
        ax.bar(xs + i * width, heights, width, label=name)
    histograms.label_bins(ax, xs + width * len(hists) / 2, counts)
    ax.set_xlabel("iterations per step")
    histograms.count_axis(ax, "steps", histograms.wants_log([h for _, h in bars]))
    ax.set_title("P3 arch-curved, implicit-fb: iterations per step beside the report's Table 2",
                 fontsize=10)
    ax.legend(fontsize=8)
    path = _save(fig, results_dir, "p3_histogram.png")
    lines += ["![P3 iteration histogram](%s)" % path, ""]


def write(results_dir, sections=()):
    """REPORT.md: P1, P2, P3, then each of `sections` (lists of markdown lines, e.g.
    readings.section), then the reconstruction choices."""
    lines = ["# Reproduction of the report's examples",
             "",
             "Generated by `results/plot.py` from the CSV records under results/ (the main job, "
             "`bash scripts/run_suite.sh`, writes both). Kanno & Ohsaki, METR 2009-06, section 5; "
             "the geometry is reconstructed as docs/problems.md describes, with every "
             "choice a parameter (listed at the end). Formulation: implicit-fb (the smoothed FB "
             "system (29)-(33) with rho an unknown), eta case 1 unless stated. Every step counted "
             "here is verified by the verdict (docs/method.md section 7), tolerance 1e-8.",
             ""]
    lines[:0] = quick.opening(results_dir)  # a quick run's report says so first
    p1(results_dir, lines)
    p2(results_dir, lines)
    p3(results_dir, lines)
    for extra in sections:
        lines += extra
    lines += ["## Reconstruction choices", "",
              "The parameters of each problem as the runs used them (parameters.csv beside the "
              "records). The load unit of P2 and P3 is a reconstruction of this suite: the report "
              "prints '5 lambda kN' and 'lambda kN' with E = 20 GPa; read in kN the limit point of "
              "P3 would lie near lambda = 1.9e5, about 10^6 arc-length steps of 0.1 away, against "
              "the report's 1604 steps, so the load unit is read as MN (`load` = 5000 and 1000 kN "
              "per unit lambda; force_scale = 1000 kN).", ""]
    for problem, sub in (("block", "eta1-newton"), ("arch-flat", "newton"),
                         ("arch-curved", "newton")):
        r = _run(results_dir, problem, sub)
        if r is not None:
            lines += ["### %s" % problem, ""]
            _reconstruction(r, lines)
    with open(os.path.join(results_dir, "REPORT.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
