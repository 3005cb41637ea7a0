"""Figures of any one `contactbench run` or `contactbench compare` directory, from its records
alone (docs/records.md), whatever the problem (named or a problem file, 2-D or 3-D, a body or
an LCP):

  path.png        the path: lambda against the control displacement, kinks and critical
                  points marked (one line per formulation x start of a comparison);
  deformed.png    the deformed shape at each saved state, the obstacles drawn (run, a body);
  cost.png        iterations and wall time per step;
  residual.png    the residual history of one step (by default the one with most iterations);
  profiles.png,   compare only: the Dolan-More profiles and the iteration histograms of the
  histograms.png  report (plotlib/comparison.py).

`write(run_dir, figures_dir, step=None)` writes them and returns their paths.
"""
import json
import os

import numpy as np
import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.collections import LineCollection  # noqa: E402

from plotlib import comparison, obstacles  # noqa: E402

RECORDS = ["steps", "iterations", "kinks", "critical", "snapshots", "snapshot_contacts",
           "cells", "runs"]
CRITICAL_MARKER = {"limit": ("v", "tab:red"), "bifurcation": ("D", "tab:purple"),
                   "stability_change": ("s", "tab:brown")}


def _read_csv(path):
    """The record file at `path` (None when missing or empty); ValueError naming the file when
    it is not a CSV file pandas can read."""
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return None
    try:
        return pd.read_csv(path)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
        raise ValueError(f"{path}: not a readable record file ({e})") from None


def read_run(run_dir):
    """The records of a run or comparison directory: a DataFrame per record file (None when
    missing or empty), `run` (run.json, {} when missing) and `dir`."""
    if not os.path.isdir(run_dir):
        raise FileNotFoundError(f"{run_dir}: no such directory")
    records = {name: _read_csv(os.path.join(run_dir, name + ".csv")) for name in RECORDS}
    if records["steps"] is None:
        raise ValueError(f"{run_dir}: no steps.csv; not the --out directory of a run or compare")
    run_json = os.path.join(run_dir, "run.json")
    try:
        with open(run_json) as f:
            records["run"] = json.load(f)
    except FileNotFoundError:
        records["run"] = {}
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise ValueError(f"{run_json}: not a readable run.json ({e})") from None
    if not isinstance(records["run"], dict):
        raise ValueError(f"{run_json}: not a run.json (not a JSON object)")
    if len(records["steps"]) == 0:
        reason = records["run"].get("reason", "")
        raise ValueError(f"{run_dir}: the run stopped before its first step; nothing to plot"
                         + (f" (run.json: {reason})" if reason else ""))
    records["dir"] = run_dir
    return records


def is_comparison(records):
    return records["runs"] is not None or records["run"].get("command") == "compare"


def _groups(steps):
    """(label, rows) per formulation x start, in the order they appear."""
    keys = list(dict.fromkeys(zip(steps["formulation"], steps["start"])))
    return [(comparison.solver_label(f, s),
             steps[(steps["formulation"] == f) & (steps["start"] == s)]) for f, s in keys]


def _save(fig, path):
    if os.path.islink(path):  # never written through, as the suite's own files (owned_file.h)
        plt.close(fig)
        raise ValueError(f"{path}: a symbolic link; plot does not write through one")
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def _problem(records):
    steps = records["steps"]
    return str(steps["problem"].iloc[0]) if len(steps) else records["run"].get("problem", "")


# --- the path ----------------------------------------------------------------------------------

def plot_path(records, path):
    """lambda against the control displacement of the accepted states, from the unloaded
    state; kinks (x) and critical points marked."""
    steps = records["steps"]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for label, g in _groups(steps):
        accepted = g[g["accepted"].astype(bool)].sort_values("step")
        x = np.concatenate([[0.0], accepted["control_disp"].to_numpy(dtype=float)])
        y = np.concatenate([[0.0], accepted["lambda"].to_numpy(dtype=float)])
        ax.plot(x, y, ".-", markersize=3, linewidth=1.2, label=label)
    kinks = records["kinks"]
    if kinks is not None and len(kinks):
        ok = kinks[kinks["verified"].astype(bool)]
        ax.plot(ok["control_disp"], ok["lambda"], "x", color="black", markersize=7,
                label=f"kinks ({len(ok)})")
    critical = records["critical"]
    if critical is not None and len(critical):
        for kind, g in critical.groupby("kind"):
            marker, colour = CRITICAL_MARKER.get(kind, ("o", "tab:gray"))
            ax.plot(g["control_disp"], g["lambda"], marker, color=colour, markersize=8,
                    markerfacecolor="none", markeredgewidth=1.6, label=f"{kind} ({len(g)})")
    ax.set_xlabel("control displacement")
    ax.set_ylabel("load parameter lambda")
    ax.set_title(f"{_problem(records)}: the path")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


# --- the deformed shapes ---------------------------------------------------------------------

def _state_segments(nodes, cells, dims):
    """The element edges of one saved state in the deformed configuration."""
    xyz = nodes[dims].to_numpy(dtype=float) + nodes[["u" + c for c in dims]].to_numpy(dtype=float)
    moved = dict(zip(nodes["node"].astype(int), xyz))
    segments = []
    for _, corners in cells.sort_values(["cell", "corner"]).groupby("cell"):
        ids = list(corners["node"])
        ring = ids if len(ids) == 2 else ids + ids[:1]
        segments += [(moved[a], moved[b]) for a, b in zip(ring, ring[1:])]
    return segments


def plot_deformed(records, path):
    """One panel per saved state (at most 6: evenly spread, the final state last); the mesh in
    its reference (grey) and deformed (colour) configurations, pairs in contact marked, and the
    obstacles. False when the run saved no state of a body."""
    snapshots, cells = records["snapshots"], records["cells"]
    if snapshots is None or cells is None or not len(snapshots):
        return None
    dims = ["x", "y", "z"] if "z" in snapshots else ["x", "y"]
    saved = list(dict.fromkeys(zip(snapshots["step"], snapshots["label"])))
    if len(saved) > 6:
        saved = [saved[int(round(i))] for i in np.linspace(0, len(saved) - 1, 6)]
    drawn = obstacles.read(records["dir"])
    columns = min(3, len(saved))
    rows = -(-len(saved) // columns)
    three_d = len(dims) == 3
    fig = plt.figure(figsize=(5.5 * columns, 4.2 * rows))
    contacts = records["snapshot_contacts"]
    for k, (step, label) in enumerate(saved):
        nodes = snapshots[(snapshots["step"] == step) & (snapshots["label"] == label)]
        ax = fig.add_subplot(rows, columns, k + 1, projection="3d" if three_d else None)
        reference = nodes.assign(**{"u" + c: 0.0 for c in dims})
        for state, style in ((reference, dict(color="0.75", lw=0.6)),
                             (nodes, dict(color="tab:blue", lw=1.0))):
            segments = _state_segments(state, cells, dims)
            if three_d:
                for a, b in segments:
                    ax.plot(*zip(a, b), **style)
            else:
                ax.add_collection(LineCollection(segments, **style))
        obstacles.draw(ax, drawn, three_d)
        if contacts is not None:
            c = contacts[(contacts["step"] == step) & (contacts["label"] == label)]
            closed = nodes[nodes["node"].isin(c[c["r"] < 0]["node"])]
            if len(closed):
                xyz = [closed[d] + closed["u" + d] for d in dims]
                ax.plot(*xyz, "o", color="tab:orange", markersize=3, linestyle="none")
        lam = float(nodes["lambda"].iloc[0])
        ax.set_title(f"step {step} ({label}), lambda = {lam:.4g}", fontsize=9)
        if not three_d:
            ax.set_aspect("equal", adjustable="datalim")
            ax.autoscale_view()
    fig.suptitle(f"{_problem(records)}: deformed shapes (grey: reference, red: obstacles, "
                 "orange: nodes in contact)")
    fig.tight_layout()
    return _save(fig, path)


# --- the cost per step and the residual history ------------------------------------------------

def plot_cost(records, path):
    """Iterations and wall time of every attempt against its step; failed attempts hollow."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for label, g in _groups(records["steps"]):
        ok = g["accepted"].astype(bool)
        for ax, column in ((top, "iterations"), (bottom, "time_s")):
            line, = ax.plot(g[ok]["step"], g[ok][column], ".-", markersize=3, linewidth=0.8,
                            label=label)
            if (~ok).any():
                ax.plot(g[~ok]["step"], g[~ok][column], "o", markerfacecolor="none",
                        color=line.get_color(), label=f"{label}: not accepted")
    top.set_ylabel("iterations")
    bottom.set_ylabel("wall time of the solve [s]")
    bottom.set_yscale("log")
    bottom.set_xlabel("step")
    for ax in (top, bottom):
        ax.grid(True, alpha=0.3)
    top.legend(fontsize=8)
    top.set_title(f"{_problem(records)}: cost per step")
    return _save(fig, path)


def hardest_step(records):
    """The step whose attempt took the most iterations (the first of equals)."""
    steps = records["steps"]
    return int(steps.loc[steps["iterations"].idxmax(), "step"])


def plot_residual(records, path, step, chosen=True):
    """norm_inf(F) of each iteration of every attempt of `step` (per formulation x start). A
    step not `chosen` by the user (the default) without iterations (a run that stopped while
    writing them) draws nothing."""
    iterations = records["iterations"]
    if iterations is None:
        return None
    rows = iterations[iterations["step"] == step]
    if not len(rows) and not chosen:
        return None
    if not len(rows):
        raise ValueError(f"step {step} has no iteration in iterations.csv "
                         f"(steps {iterations['step'].min()}-{iterations['step'].max()})")
    fig, ax = plt.subplots(figsize=(8, 5))
    for label, g in _groups(rows):
        for attempt, a in g.groupby("attempt"):
            name = label if attempt == 0 else f"{label}, attempt {attempt}"
            ax.semilogy(a["iteration"], a["residual_inf"].clip(lower=1e-300), "o-",
                        markersize=3, label=name)
    ax.set_xlabel("iteration")
    ax.set_ylabel("norm_inf(F) of the formulation's system")
    ax.set_title(f"{_problem(records)}: residual history of step {step}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


# --- all of them -----------------------------------------------------------------------------

def write(run_dir, figures_dir, step=None):
    """Every figure that the directory's records allow; returns the paths written."""
    records = read_run(run_dir)
    if os.path.exists(figures_dir) and not os.path.isdir(figures_dir):
        raise ValueError(f"--figures: '{figures_dir}' exists and is not a directory")
    os.makedirs(figures_dir, exist_ok=True)
    out = os.path.join
    written = [plot_path(records, out(figures_dir, "path.png")),
               plot_deformed(records, out(figures_dir, "deformed.png")),
               plot_cost(records, out(figures_dir, "cost.png")),
               plot_residual(records, out(figures_dir, "residual.png"),
                             hardest_step(records) if step is None else step,
                             chosen=step is not None)]
    runs = records["runs"]
    if is_comparison(records) and runs is not None:
        steps = records["steps"]
        title = f"{_problem(records)} ({os.path.basename(os.path.normpath(run_dir))})"
        profiles = out(figures_dir, "profiles.png")
        if comparison.plot_profiles(title, title, runs, steps, profiles):
            written.append(profiles)
        histograms = out(figures_dir, "histograms.png")
        if comparison.plot_histograms(title, runs, steps, histograms,
                                      comparison.iteration_word_for(runs)):
            written.append(histograms)
    return [p for p in written if p]
