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
from mpl_toolkits.mplot3d.art3d import Line3DCollection  # noqa: E402

from plotlib import comparison, obstacles, styles  # noqa: E402

RECORDS = ["steps", "iterations", "kinks", "critical", "snapshots", "snapshot_contacts",
           "cells", "runs"]
CRITICAL_MARKER = {"limit": ("v", "tab:red"), "bifurcation": ("D", "tab:purple"),
                   "stability_change": ("s", "tab:brown")}
# The legend's words for critical.csv's kinds.
CRITICAL_WORDS = {"limit": "limit points", "bifurcation": "bifurcation points",
                  "stability_change": "changes of stability"}


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
    """(label, rows, style) per formulation x start, in the order they appear: the style the
    formulation's fixed colour and marker (plotlib/styles.py), dashed for a cold start."""
    keys = list(dict.fromkeys(zip(steps["formulation"], steps["start"])))
    return [(comparison.solver_label(f, s),
             steps[(steps["formulation"] == f) & (steps["start"] == s)],
             dict(styles.style(f), linestyle="--" if s == "cold" else "-")) for f, s in keys]


def control_label(records):
    """What control_disp is, from run.json's `control` (the problem's label, with its unit)."""
    control = records["run"].get("control")
    return control if control else "control displacement (in the problem's length unit)"


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
    for label, g, style in _groups(steps):
        accepted = g[g["accepted"].astype(bool)].sort_values("step")
        x = np.concatenate([[0.0], accepted["control_disp"].to_numpy(dtype=float)])
        y = np.concatenate([[0.0], accepted["lambda"].to_numpy(dtype=float)])
        ax.plot(x, y, markersize=3, linewidth=1.2, label=label,
                markevery=max(1, len(x) // 20), **style)
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
                    markerfacecolor="none", markeredgewidth=1.6,
                    label=f"{CRITICAL_WORDS.get(kind, kind)} ({len(g)})")
    ax.set_xlabel(control_label(records))
    ax.set_ylabel("load parameter lambda")
    ax.set_title(f"{_problem(records)}: the path")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


# --- the deformed shapes ---------------------------------------------------------------------

# The edges of each element kind by its corners (VTK/Gmsh corner order): a hexahedron's twelve
# (0-3 one face, 4-7 the other), a tetrahedron's six, a polygon's ring, a member's one.
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7)]
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]


def element_edges(corners, dim):
    """The corner pairs joined by an edge in an element of `corners` corners in `dim` D."""
    if corners == 8:
        return HEX_EDGES
    if corners == 4 and dim == 3:
        return TET_EDGES
    if corners == 2:
        return [(0, 1)]
    return [(k, (k + 1) % corners) for k in range(corners)]


def _state_segments(nodes, cells, dims):
    """The element edges of one saved state in the deformed configuration, an array
    (edges x 2 x len(dims)): each element's edges in turn (element_edges), the elements of one
    kind together, in the order of their ids."""
    xyz = nodes[dims].to_numpy(dtype=float) + nodes[["u" + c for c in dims]].to_numpy(dtype=float)
    point = pd.Series(np.arange(len(nodes)), index=nodes["node"].astype(int).to_numpy())
    ordered = cells.sort_values(["cell", "corner"])
    size = ordered.groupby("cell")["corner"].transform("size")
    parts = []
    for corners, kind in ordered.groupby(size, sort=True):
        ids = point.loc[kind["node"].astype(int).to_numpy()].to_numpy().reshape(-1, corners)
        edges = np.array(element_edges(corners, len(dims)))
        ends = np.stack([xyz[ids[:, edges[:, 0]]], xyz[ids[:, edges[:, 1]]]], axis=2)
        parts.append(ends.reshape(-1, 2, len(dims)))
    return np.concatenate(parts) if parts else np.zeros((0, 2, len(dims)))


# A hexahedron's six faces (corner order as HEX_EDGES).
HEX_FACES = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def outer_edges(cells):
    """The node pairs (n x 2, ascending) of the edges on a solid's outer surface: the edges of
    the hexahedra's faces that belong to one hexahedron only, each once. What a 3-D figure
    draws: the inner edges of a mesh only hide its surface and the contact patch."""
    ordered = cells.sort_values(["cell", "corner"])
    hexes = ordered.groupby("cell").filter(lambda c: len(c) == 8) if len(ordered) else ordered
    ids = hexes["node"].astype(int).to_numpy().reshape(-1, 8)
    faces = np.concatenate([ids[:, list(f)] for f in HEX_FACES])
    key = np.sort(faces, axis=1)
    _, first, count = np.unique(key, axis=0, return_index=True, return_counts=True)
    outer = faces[first[count == 1]]
    pairs = np.concatenate([outer[:, [k, (k + 1) % 4]] for k in range(4)])
    return np.unique(np.sort(pairs, axis=1), axis=0)


def _outer_segments(nodes, edges, dims, scale=1.0):
    """The segments of `edges` (node pairs) with the nodes moved by `scale` times u."""
    n = nodes.set_index(nodes["node"].astype(int))
    xyz = n[dims].to_numpy(dtype=float) + scale * n[["u" + c for c in dims]].to_numpy(dtype=float)
    point = pd.Series(np.arange(len(n)), index=n.index)
    at = point.loc[edges.ravel()].to_numpy().reshape(-1, 2)
    return np.stack([xyz[at[:, 0]], xyz[at[:, 1]]], axis=1)


def display_scale(nodes, dims):
    """The factor the displacements of a 3-D figure are drawn with: 1 when the largest is at
    least 2 % of the body's size, else the factor that makes it 5 % (a Hertz contact's
    indentation is invisible to scale)."""
    size = float((nodes[dims].max() - nodes[dims].min()).max())
    largest = float(np.sqrt((nodes[["u" + c for c in dims]] ** 2).sum(axis=1)).max())
    if largest <= 0.0 or largest >= 0.02 * size:
        return 1.0
    return float(f"{0.05 * size / largest:.1g}")


def _distinct_states(snapshots):
    """(step, label) of the saved states to draw: one per step (the last label saved there,
    so that the final state replaces the regular save of its step), at most 5 evenly spread
    with the last one kept."""
    saved = list(dict.fromkeys(zip(snapshots["step"], snapshots["label"])))
    last = {step: label for step, label in saved}
    saved = [(step, label) for step, label in saved if last[step] == label]
    saved = list(dict.fromkeys(saved))
    if len(saved) > 5:
        saved = [saved[int(round(i))] for i in np.linspace(0, len(saved) - 1, 5)]
    return saved


def _body_box(nodes, dims, margin=0.15):
    """(low, high) around the body's reference and deformed nodes, `margin` of each side each
    way (at least a twentieth of the largest side): the window of a panel (obstacles may reach
    far beyond the body)."""
    reference = nodes[dims].to_numpy(dtype=float)
    moved = reference + nodes[["u" + c for c in dims]].to_numpy(dtype=float)
    both = np.vstack([reference, moved])
    low, high = both.min(axis=0), both.max(axis=0)
    side = high - low
    pad = np.maximum(margin * side, 0.05 * max(float(side.max()), 1e-12))
    return low - pad, high + pad


def _contact_points(contacts, nodes, dims, step, label):
    if contacts is None:
        return None
    c = contacts[(contacts["step"] == step) & (contacts["label"] == label)]
    closed = nodes[nodes["node"].isin(c[c["r"] < 0]["node"])]
    if not len(closed):
        return None
    return [closed[d] + closed["u" + d] for d in dims]


def _panel_2d(ax, nodes, cells, dims, drawn, contacts, step, label):
    reference = nodes.assign(**{"u" + c: 0.0 for c in dims})
    ax.add_collection(LineCollection(_state_segments(reference, cells, dims), color="0.75",
                                     lw=0.6, label="reference"))
    ax.add_collection(LineCollection(_state_segments(nodes, cells, dims), color="tab:blue",
                                     lw=1.0, label="deformed"))
    obstacles.draw(ax, drawn)
    closed = _contact_points(contacts, nodes, dims, step, label)
    if closed is not None:
        ax.plot(*closed, "o", color="tab:orange", markersize=3, linestyle="none",
                label="nodes in contact")
    low, high = _body_box(nodes, dims)
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (the problem's length unit)")
    ax.set_ylabel("y")


def _panel_3d(ax, nodes, edges, dims, drawn, closed, colour):
    """One state of a solid: the edges of its outer surface as one collection, the obstacles'
    faces inside the window as another, the nodes in contact marked; the window is the body's."""
    low, high = _body_box(nodes, dims)
    ax.add_collection3d(Line3DCollection(_outer_segments(nodes, edges, dims), colors=colour,
                                         linewidths=0.5))
    obstacles.draw_3d(ax, drawn, low, high)
    if closed is not None:
        ax.plot(*closed, "o", color="tab:orange", markersize=2, linestyle="none")
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_zlim(low[2], high[2])
    ax.set_box_aspect(high - low)
    ax.view_init(elev=-25, azim=-60)  # from below: the contact face and its patch
    for axis, name in zip("xyz", dims):
        getattr(ax, f"set_{axis}label")(name, fontsize=8)
    ax.tick_params(labelsize=6)


def plot_deformed(records, path):
    """One panel per distinct saved state (at most 5, the final state last). 2-D: the mesh in
    its reference (grey) and deformed (blue) configurations over each other; 3-D: the reference
    configuration in a panel of its own (grey) first, then the deformed ones (blue), each drawn
    by its elements' edges. The obstacles in red, the nodes in contact in orange; every window
    framed on the body. None when the run saved no state of a body."""
    snapshots, cells = records["snapshots"], records["cells"]
    if snapshots is None or cells is None or not len(snapshots):
        return None
    dims = ["x", "y", "z"] if "z" in snapshots else ["x", "y"]
    three_d = len(dims) == 3
    saved = _distinct_states(snapshots)
    panels = ([None] if three_d else []) + saved  # None: the reference configuration
    drawn = obstacles.read(records["dir"])
    low, high = _body_box(snapshots, dims)
    wide = (high[0] - low[0]) / max(high[1] - low[1], 1e-12)  # a flat arch: 15 to 1
    if not three_d and wide > 3.0:  # one wide panel a row: at 3 a row the body is a line
        columns, panel = 1, (14.0, min(4.2, max(1.6, 14.0 / wide + 0.9)))
    else:
        columns, panel = min(3, len(panels)), (5.5, 4.2)
    rows = -(-len(panels) // columns)
    fig = plt.figure(figsize=(panel[0] * columns, panel[1] * rows))
    contacts = records["snapshot_contacts"]
    edges = outer_edges(cells) if three_d else None
    scale = display_scale(snapshots, dims) if three_d else 1.0
    for k, panel in enumerate(panels):
        step, label = panel if panel is not None else saved[0]
        nodes = snapshots[(snapshots["step"] == step) & (snapshots["label"] == label)]
        ax = fig.add_subplot(rows, columns, k + 1, projection="3d" if three_d else None)
        if panel is None:
            _panel_3d(ax, nodes.assign(**{"u" + c: 0.0 for c in dims}), edges, dims, drawn, None,
                      "0.55")
            ax.set_title("reference configuration", fontsize=9, y=1.1)
            continue
        if three_d:
            shown = nodes.assign(**{"u" + c: scale * nodes["u" + c] for c in dims})
            _panel_3d(ax, shown, edges, dims, drawn,
                      _contact_points(contacts, shown, dims, step, label), "tab:blue")
        else:
            _panel_2d(ax, nodes, cells, dims, drawn, contacts, step, label)
        lam = float(nodes["lambda"].iloc[0])
        ax.set_title(f"step {step} ({label}), lambda = {lam:.4g}", fontsize=9,
                     y=1.1 if three_d else 1.0)
    shown = "displacements to scale" if scale == 1.0 else f"displacements x {scale:g}"
    if three_d:
        key = "grey: reference, blue: deformed (outer surface)"
    else:
        key = "grey: reference, blue: deformed"
    fig.suptitle(f"{_problem(records)}: deformed shapes ({key}, red: obstacles, orange: nodes "
                 f"in contact; {shown})", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.4 / fig.get_figheight()))
    return _save(fig, path)


# --- the cost per step and the residual history ------------------------------------------------

def plot_cost(records, path):
    """Iterations and wall time of every attempt against its step; failed attempts hollow."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for label, g, style in _groups(records["steps"]):
        ok = g["accepted"].astype(bool)
        for ax, column in ((top, "iterations"), (bottom, "time_s")):
            line, = ax.plot(g[ok]["step"], g[ok][column], markersize=3, linewidth=0.8,
                            label=label, markevery=max(1, int(ok.sum()) // 20), **style)
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
    for label, g, style in _groups(rows):
        for attempt, a in g.groupby("attempt"):
            name = label if attempt == 0 else f"{label}, attempt {attempt}"
            ax.semilogy(a["iteration"], a["residual_inf"].clip(lower=1e-300), markersize=3,
                        label=name, **dict(style, alpha=1.0 if attempt == 0 else 0.5))
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
