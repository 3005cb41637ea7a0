"""The three-dimensional solids: the section "Three-dimensional solids" of RESULTS_DIR/REPORT.md
and its figures (docs/problems.md, "Three-dimensional solids and `hertz-3d`").

`section(results_dir)` reads the records of scripts/run_solid3d.sh,
  results_dir/solid3d/hertz/n<N>/   hertz-3d on N x N x N hexahedra (implicit-fb, the fixed-load
                                    solve), one directory per mesh
  results_dir/solid3d/plate-3d/     plate-3d's arc-length path, kinks located, states saved
and returns the section's markdown lines (None when there are no such records), writing its
figures into results_dir/figures/solid3d/:
  hertz.png            the contact pressure along the radius against Hertz's closed form, and
                       the errors of the contact radius and the peak pressure against the mesh;
  plate-path.png       lambda against the control displacement and the pairs in contact
                       against lambda, kinks marked;
  plate-deformed.png   the plate seen from the side at the saved states, the cylinder drawn.

The Hertz measures are those of src/problems/hertz.cc's MeasureHertzContact: the contact radius
from the second moment of the nodal reactions (sum |r| rho^2 / sum |r| = 2 a^2 / 5 for Hertz's
pressure), the peak pressure as the reaction of the node at the origin over its tributary area
(a quarter of the first cell).
"""
import glob
import math
import os
import re
import shutil

import numpy as np
import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from plotlib import run_plots  # noqa: E402

FIGURES = os.path.join("figures", "solid3d")
COMMAND = "bash scripts/run_solid3d.sh && /usr/bin/python3 results/plot.py"
# A second rate is fitted from this mesh on, the finer meshes (the table says where the errors
# grow).
FIT_FROM = 16


# --- Hertz: the closed form and the measures ---------------------------------------------------

def closed_form(force, radius, youngs_modulus, poisson_ratio):
    """Hertz's contact radius a = (3 P R / (4 E*))^(1/3), E* = E / (1 - nu^2), and peak pressure
    p0 = 3 P / (2 pi a^2)."""
    e_star = youngs_modulus / (1.0 - poisson_ratio ** 2)
    a = (3.0 * force * radius / (4.0 * e_star)) ** (1.0 / 3.0)
    return a, 3.0 * force / (2.0 * math.pi * a * a)


def _tributary_widths(coordinates):
    """Half the distance between each coordinate's neighbours on the sorted grid line (half a
    cell at either end): the side of the node's tributary area along that axis."""
    c = np.unique(coordinates)
    if len(c) < 2:
        return {c[0]: 0.0} if len(c) else {}
    edges = np.concatenate([[c[0]], 0.5 * (c[1:] + c[:-1]), [c[-1]]])
    return dict(zip(c, edges[1:] - edges[:-1]))


def nodal_pressures(solution, contacts):
    """The bottom face's nodes: rho (distance from the contact point) and the pressure, the
    nodal reaction over the node's tributary area, sorted by rho."""
    xy = solution.set_index("node")[["x", "y"]]
    c = contacts.join(xy, on="node")
    wx, wy = _tributary_widths(c["x"].to_numpy()), _tributary_widths(c["y"].to_numpy())
    area = np.array([wx[x] * wy[y] for x, y in zip(c["x"], c["y"])])
    out = pd.DataFrame({"rho": np.hypot(c["x"], c["y"]), "pressure": -c["r"].to_numpy() / area})
    return out.sort_values("rho").reset_index(drop=True)


def measure(solution, contacts):
    """(a, p0) of one solve, as MeasureHertzContact."""
    c = contacts.join(solution.set_index("node")[["x", "y"]], on="node")
    force = -c["r"].to_numpy()
    rho2 = (c["x"] ** 2 + c["y"] ** 2).to_numpy()
    at_origin = force[(c["x"] == 0.0).to_numpy() & (c["y"] == 0.0).to_numpy()].sum()
    first_x = c["x"][c["x"] > 0.0].min()
    first_y = c["y"][c["y"] > 0.0].min()
    return (math.sqrt(2.5 * (force * rho2).sum() / force.sum()),
            at_origin / (0.25 * first_x * first_y))


def observed_rates(n, error):
    """The observed order between successive meshes, log(|e_k| / |e_k+1|) / log(n_k+1 / n_k)
    (h ~ 1/n at fixed grading); NaN where either error is zero. The first mesh has none."""
    rates = [math.nan]
    for (n0, e0), (n1, e1) in zip(zip(n, error), zip(n[1:], error[1:])):
        ok = e0 != 0.0 and e1 != 0.0
        rates.append(math.log(abs(e0) / abs(e1)) / math.log(n1 / n0) if ok else math.nan)
    return rates


def fitted_rate(n, error):
    """The least-squares slope of -log|e| against log n over the meshes given."""
    if len(n) < 2:
        return math.nan
    return -float(np.polyfit(np.log(n), np.log(np.abs(error)), 1)[0])


# --- the records ---------------------------------------------------------------------------

def _parameters(run_dir):
    p = pd.read_csv(os.path.join(run_dir, "parameters.csv"), dtype=str, keep_default_na=False)
    return dict(zip(p["name"], p["value"]))


def _verified(run_dir):
    steps = run_plots._read_csv(os.path.join(run_dir, "steps.csv"))
    if steps is None:
        return False
    accepted = steps[steps["accepted"].astype(str).str.lower() == "true"]
    return len(accepted) > 0 and accepted["verified"].astype(str).str.lower().eq("true").all()


def hertz_table(results_dir):
    """One row per verified hertz-3d mesh (n ascending): n, d, nc, a, p0, their relative errors
    and observed rates; plus each run's directory. None without records."""
    rows = []
    for run_dir in glob.glob(os.path.join(results_dir, "solid3d", "hertz", "n*")):
        if not re.fullmatch(r"n\d+", os.path.basename(run_dir)) or not _verified(run_dir):
            continue
        p = _parameters(run_dir)
        a_ref, p_ref = closed_form(float(p["force"]), float(p["sphere_radius"]),
                                   float(p["youngs_modulus"]), float(p["poisson_ratio"]))
        solution = pd.read_csv(os.path.join(run_dir, "solution.csv"))
        contacts = pd.read_csv(os.path.join(run_dir, "contacts.csv"))
        a, p0 = measure(solution, contacts)
        rows.append({"n": int(p["n"]), "nz": int(p["nz"]), "d": int(p["num_dofs"]),
                     "nc": int(p["num_pairs"]), "a": a, "p0": p0, "a_ref": a_ref, "p0_ref": p_ref,
                     "error_a": a / a_ref - 1.0, "error_p0": p0 / p_ref - 1.0, "dir": run_dir})
    if not rows:
        return None
    table = pd.DataFrame(rows).sort_values("n").reset_index(drop=True)
    table["rate_a"] = observed_rates(list(table["n"]), list(table["error_a"]))
    table["rate_p0"] = observed_rates(list(table["n"]), list(table["error_p0"]))
    return table


# --- the thinned records -----------------------------------------------------------------------

# What the section reads: of a hertz-3d mesh, its parameters, steps, contacts and the nodes in
# contact (their coordinates; the states, cells and VTK files are not read); of plate-3d,
# everything but the VTK files.
HERTZ_KEPT_FILES = ("parameters.csv", "steps.csv", "contacts.csv", "solution.csv", "run.json",
                    "kinks.csv", "critical.csv")


def _remove(path):
    shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)


def thin_records(results_dir):
    """Rewrites the records of scripts/run_solid3d.sh in place to what the section reads (a
    hertz-3d mesh's solution.csv: the rows of the nodes in contacts.csv, as recorded)."""
    for run_dir in glob.glob(os.path.join(results_dir, "solid3d", "hertz", "n*")):
        path = os.path.join(run_dir, "solution.csv")
        if os.path.isfile(path) and os.path.isfile(os.path.join(run_dir, "contacts.csv")):
            nodes = set(pd.read_csv(os.path.join(run_dir, "contacts.csv"), dtype=str)["node"])
            text = pd.read_csv(path, dtype=str, keep_default_na=False)
            text[text["node"].isin(nodes)].to_csv(path, index=False)
        for name in os.listdir(run_dir):
            if name not in HERTZ_KEPT_FILES:
                _remove(os.path.join(run_dir, name))
    vtk = os.path.join(results_dir, "solid3d", "plate-3d", "vtk")
    if os.path.isdir(vtk):
        _remove(vtk)


# --- figures -------------------------------------------------------------------------------

def _save(fig, results_dir, name):
    """Saves `fig` as FIGURES/name under results_dir; returns that path relative to it."""
    os.makedirs(os.path.join(results_dir, FIGURES), exist_ok=True)
    run_plots._save(fig, os.path.join(results_dir, FIGURES, name))
    return os.path.join(FIGURES, name)


def hertz_figure(results_dir, table):
    """Left: the nodal pressures of the finest and a coarse mesh against p0 sqrt(1 - rho^2/a^2);
    right: |error| of a and p0 against n, log-log, with slopes 1 and 2 for reference."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6))
    a_ref, p_ref = table["a_ref"].iloc[0], table["p0_ref"].iloc[0]
    rho = np.linspace(0.0, a_ref, 200)
    left.plot(rho, p_ref * np.sqrt(1.0 - (rho / a_ref) ** 2), "k-", lw=1.6,
              label="Hertz: p0 sqrt(1 - rho^2 / a^2)")
    shown = table.iloc[[len(table) - 1]] if len(table) < 3 else table.iloc[[1, len(table) - 1]]
    for (_, row), style in zip(shown.iterrows(), ("s", "o")):
        solution = pd.read_csv(os.path.join(row["dir"], "solution.csv"))
        contacts = pd.read_csv(os.path.join(row["dir"], "contacts.csv"))
        pressures = nodal_pressures(solution, contacts)
        near = pressures[pressures["rho"] <= 2.0 * a_ref]
        left.plot(near["rho"], near["pressure"], style, ms=4, mfc="none",
                  label="%d^3 (d = %d): nodal reaction / tributary area" % (row["n"], row["d"]))
    left.set_xlabel("rho, distance from the contact point [mm]")
    left.set_ylabel("contact pressure [N/mm^2]")
    left.set_xlim(0.0, 2.0 * a_ref)
    left.set_title("hertz-3d: pressure on the bottom face, every node (a = %.4f mm)" % a_ref,
                   fontsize=10)
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8)
    n = table["n"].to_numpy(dtype=float)
    right.loglog(n, 100 * np.abs(table["error_a"]), "o-", label="contact radius a")
    right.loglog(n, 100 * np.abs(table["error_p0"]), "s-", label="peak pressure p0")
    for order, style in ((1, ":"), (2, "--")):
        start = 100 * abs(table["error_a"].iloc[0])
        right.loglog(n, start * (n / n[0]) ** -order, "k" + style, lw=0.8,
                     label="slope -%d" % order)
    right.set_xticks(n, minor=False)
    right.set_xticks([], minor=True)
    right.set_xticklabels(["%d" % v for v in n])
    right.set_xlabel("n (n x n x n hexahedra; h ~ 1/n)")
    right.set_ylabel("|relative error| [%]")
    right.set_title("hertz-3d: error against Hertz's closed form", fontsize=10)
    right.grid(True, which="both", alpha=0.3)
    right.legend(fontsize=8)
    return _save(fig, results_dir, "hertz.png")


# The twelve edges of a hexahedron, corners in the VTK/Gmsh order (0-3 one face, 4-7 the other).
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7)]


def side_view_segments(nodes, cells, amplification=1.0):
    """The hexahedra's edges projected on the x-z plane, the nodes moved by `amplification` u."""
    n = nodes.set_index("node")
    xz = (n[["x", "z"]].to_numpy(dtype=float)
          + amplification * n[["ux", "uz"]].to_numpy(dtype=float))
    where = {node: i for i, node in enumerate(n.index)}
    segments = []
    for _, corners in cells.sort_values(["cell", "corner"]).groupby("cell"):
        ids = [where[c] for c in corners["node"]]
        segments += [(xz[ids[a]], xz[ids[b]]) for a, b in HEX_EDGES]
    return segments


def plate_path_figure(results_dir, records, control_label):
    """Left: lambda against the control displacement, kinks marked; right: the pairs in contact
    against lambda (each kink a pair closing), the kinks' lambda marked."""
    steps, kinks = records["steps"], records["kinks"]
    accepted = steps[steps["accepted"].astype(str).str.lower() == "true"].sort_values("step")
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6))
    x = np.concatenate([[0.0], accepted["control_disp"].to_numpy(dtype=float)])
    lam = np.concatenate([[0.0], accepted["lambda"].to_numpy(dtype=float)])
    left.plot(x, lam, ".-", ms=3, lw=1.2, label="implicit-fb, accepted steps")
    right.step(lam, np.concatenate([[0], accepted["n_contact"].to_numpy()]), where="post",
               lw=1.2, label="pairs in contact")
    if kinks is not None and len(kinks):
        left.plot(kinks["control_disp"], kinks["lambda"], "x", color="black", ms=8,
                  label="kinks (%d)" % len(kinks))
        for k, value in enumerate(sorted(kinks["lambda"])):
            right.axvline(value, color="0.5", lw=0.6, ls=":",
                          label="kinks (%d)" % len(kinks) if k == 0 else None)
    left.xaxis.set_major_locator(MaxNLocator(6))
    left.set_xlabel(control_label)
    left.set_ylabel("load parameter lambda")
    left.set_title("plate-3d: the path (the control node rests on the cylinder from its first "
                   "kink on)", fontsize=9)
    right.set_xlabel("load parameter lambda")
    right.set_ylabel("pairs in contact (of %d)" % records["contacts_total"])
    right.set_title("plate-3d: the contact spreading, one kink per closing pair", fontsize=9)
    for ax in (left, right):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    return _save(fig, results_dir, "plate-path.png")


def plate_deformed_figure(results_dir, records, parameters):
    """The plate seen from the side (x-z) at each saved state, the cylinder's section drawn, the
    nodes in contact marked."""
    snapshots, cells, contacts = (records["snapshots"], records["cells"],
                                  records["snapshot_contacts"])
    if snapshots is None or cells is None or not len(snapshots):
        return None
    saved = list(dict.fromkeys(zip(snapshots["step"], snapshots["label"])))
    saved = [s for s in saved if s[1] != "final" or (s[0], "step") not in saved]
    fig, ax = plt.subplots(figsize=(12, 4.2))
    first = snapshots[snapshots["step"] == saved[0][0]]
    ax.add_collection(LineCollection(side_view_segments(first, cells, 0.0), color="0.8", lw=0.6,
                                     label="reference"))
    colours = plt.cm.viridis(np.linspace(0.0, 0.85, len(saved)))
    for (step, label), colour in zip(saved, colours):
        nodes = snapshots[(snapshots["step"] == step) & (snapshots["label"] == label)]
        lam = float(nodes["lambda"].iloc[0])
        ax.add_collection(LineCollection(side_view_segments(nodes, cells), color=colour, lw=0.8,
                                         label="step %d, lambda = %.3g" % (step, lam)))
        if contacts is not None:
            c = contacts[(contacts["step"] == step) & (contacts["label"] == label)]
            closed = nodes[nodes["node"].isin(c[c["r"] < 0]["node"])]
            ax.plot(closed["x"] + closed["ux"], closed["z"] + closed["uz"], "o", color=colour,
                    ms=3, mfc="none")
    span, radius = float(parameters["span"]), float(parameters["cylinder_radius"])
    centre_z = -float(parameters["clearance"]) - radius
    x = np.linspace(0.0, span, 400)
    ax.plot(x, centre_z + np.sqrt(np.maximum(radius ** 2 - (x - 0.5 * span) ** 2, 0.0)), "-",
            color="tab:red", lw=1.4, label="cylinder (radius %g m)" % radius)
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("plate-3d seen from the side (all hexahedra projected on x-z; circles: nodes "
                 "in contact)", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left", ncol=2)
    return _save(fig, results_dir, "plate-deformed.png")


def plate_figures(results_dir, run_dir):
    """plate-3d's path and deformed shapes; returns the records and the two figures' paths."""
    records = run_plots.read_run(run_dir)
    parameters = _parameters(run_dir)
    records["contacts_total"] = int(parameters["num_pairs"])
    control = "z-displacement of the bottom mid-span node [m]"
    return (records, plate_path_figure(results_dir, records, control),
            plate_deformed_figure(results_dir, records, parameters))


# --- the section ---------------------------------------------------------------------------

def _percent(x):
    return "%+.2f %%" % (100.0 * x)


def _rate(x):
    return "" if math.isnan(x) else "%.2f" % x


def error_growth(n, error):
    """The successive meshes (n_k, n_k+1) between which |error| grows."""
    pairs = list(zip(zip(n, error), zip(n[1:], error[1:])))
    return [(n0, n1) for (n0, e0), (n1, e1) in pairs if abs(e1) > abs(e0)]


def _monotone_text(table):
    """Where the errors do not fall from one mesh to the next, from the table."""
    n = list(table["n"])
    parts = []
    for name, column in (("a", "error_a"), ("p0", "error_p0")):
        grows = error_growth(n, list(table[column]))
        where = ", ".join("%d to %d" % g for g in grows)
        trend = "grows from n = " + where if grows else "falls from every mesh to the next"
        parts.append("|error %s| %s" % (name, trend))
    return ("%s (why it need not fall monotonically: docs/problems.md, the edge of the contact "
            "area between nodes)." % "; ".join(parts))


def _hertz_lines(results_dir, table):
    a_ref, p_ref = table["a_ref"].iloc[0], table["p0_ref"].iloc[0]
    lines = ["### `hertz-3d`: an elastic block on a rigid sphere", "",
             "The quarter block on Hertz's paraboloid gap, small deformation, one fixed-load solve "
             "by implicit-fb (Newton) per mesh, every solve verified. Hertz: a = %.4f mm, "
             "p0 = %.3f N/mm^2. The rate is the observed order between a mesh and the one "
             "before it, log(|e_k| / |e_k+1|) / log(n_k+1 / n_k)." % (a_ref, p_ref), "",
             "| n x n x n | d | nc | a [mm] | error a | rate a | p0 [N/mm^2] | error p0 "
             "| rate p0 |",
             "|---|---|---|---|---|---|---|---|---|"]
    for _, r in table.iterrows():
        lines.append("| %d | %d | %d | %.4f | %s | %s | %.3f | %s | %s |"
                     % (r["n"], r["d"], r["nc"], r["a"], _percent(r["error_a"]),
                        _rate(r["rate_a"]), r["p0"], _percent(r["error_p0"]), _rate(r["rate_p0"])))
    fits = []
    for label, rows in (("all meshes", table), ("n >= %d" % FIT_FROM,
                                                table[table["n"] >= FIT_FROM])):
        if len(rows) >= 2:
            fits.append("%s |error a| ~ n^-%.2f, |error p0| ~ n^-%.2f"
                        % (label, fitted_rate(rows["n"], rows["error_a"]),
                           fitted_rate(rows["n"], rows["error_p0"])))
    lines += ["", "Least-squares fits of log |error| against log n: %s. %s" % (
        "; ".join(fits) or "too few meshes", _monotone_text(table)), ""]
    lines += ["![hertz-3d against Hertz](%s)" % hertz_figure(results_dir, table), ""]
    return lines


def _pair_positions(run_dir):
    """{pair: x of its node in the reference configuration}."""
    contacts = pd.read_csv(os.path.join(run_dir, "contacts.csv"))
    x = pd.read_csv(os.path.join(run_dir, "solution.csv")).set_index("node")["x"]
    return dict(zip(contacts["pair"], x.loc[contacts["node"]].to_numpy()))


def _plate_lines(results_dir, run_dir):
    records, path, deformed = plate_figures(results_dir, run_dir)
    steps, kinks = records["steps"], records["kinks"]
    accepted = steps[steps["accepted"].astype(str).str.lower() == "true"]
    lines = ["### `plate-3d`: a thick plate pressed onto a cylinder", "",
             "Neo-Hookean hexahedra in large deformation, traced by arc length with implicit-fb "
             "(Newton): %d steps accepted, lambda = %.3f at the end." % (len(accepted),
                                                                         accepted["lambda"].max()),
             ""]
    if kinks is not None and len(kinks):
        ok = kinks[kinks["verified"].astype(str).str.lower() == "true"]
        x_of_pair = _pair_positions(run_dir)
        lines += ["%d kinks located, %d verified (a pair closing between two steps, located "
                  "on the segment; kinks.csv). Grouped by the step they fall in, with the x of "
                  "the closing nodes (the cylinder's top is at x = %g m):"
                  % (len(kinks), len(ok), 0.5 * float(_parameters(run_dir)["span"])), "",
                  "| step | pairs | lambda | x of the nodes [m] |", "|---|---|---|---|"]
        for step, g in kinks.groupby("step"):
            xs = sorted({round(x_of_pair[p], 6) for p in g["pair"]})
            lines.append("| %d | %d | %.4g - %.4g | %s |"
                         % (step, len(g), g["lambda"].min(), g["lambda"].max(),
                            ", ".join("%g" % x for x in xs)))
        lines.append("")
    lines += ["![plate-3d: the path](%s)" % path, ""]
    if deformed:
        lines += ["![plate-3d: the deformed plate](%s)" % deformed, ""]
    return lines


def section(results_dir):
    """The REPORT.md section of the 3-D problems, or None when their records are absent."""
    table = hertz_table(results_dir)
    plate = os.path.join(results_dir, "solid3d", "plate-3d")
    has_plate = os.path.isfile(os.path.join(plate, "steps.csv"))
    if table is None and not has_plate:
        return None
    lines = ["## Three-dimensional solids", "",
             "Eight-node hexahedra against rigid obstacles (docs/problems.md, \"Three-dimensional "
             "solids\"). Made by `%s`." % COMMAND, ""]
    if table is not None:
        lines += _hertz_lines(results_dir, table)
    if has_plate:
        lines += _plate_lines(results_dir, plate)
    return lines
