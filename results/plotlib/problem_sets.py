"""Problem sets: the section of COMPARISON.md on collections of fixed-load problems (FCLIB files).

Reads only results_dir/compare/<set>/problems.csv and run.json, written by
`contactbench compare --problem-dir` (scripts/run_compare.sh, set `fclib`; docs/comparison.md
"Problem sets"): one row per problem x formulation x start, each a single fixed-load solve
judged by the verdict. Per set:
  - per formulation and start: problems solved (status verified) of those it took, those it
    refused, the median iterations and the median time over the solved ones with the range of
    their timed repetitions (time_min_s, time_max_s), and the median and largest FCLIB error
    (natural-map residual relative to the data; src/verdict/natural_map_error.h) of the solved
    answers;
  - Dolan-More performance profiles over the problems of the cold start, of time and of
    iterations (a failure has ratio infinity; a formulation that refused every problem is left
    out and named).
"""
import glob
import json
import math
import os

import numpy as np
import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

from plotlib import aggregation  # noqa: E402

RECORD = "problems.csv"


def problem_sets(results_dir):
    """(name, rows, run) per problem-set directory under results_dir/compare, sorted by name;
    `run` is its run.json ({} when missing)."""
    root = os.path.join(results_dir, "compare")
    found = []
    for path in sorted(glob.glob(os.path.join(root, "**", RECORD), recursive=True)):
        d = os.path.dirname(path)
        run = {}
        if os.path.exists(os.path.join(d, "run.json")):
            with open(os.path.join(d, "run.json")) as f:
                run = json.load(f)
        found.append((os.path.relpath(d, root), pd.read_csv(path), run))
    return found


def start_kind(start):
    """cold, or guess for every guess:K (one row of the table for all of a set's guesses)."""
    return "guess" if str(start).startswith("guess:") else str(start)


def summary_table(rows):
    """One row per formulation x start kind: taken, solved, refused, medians and ranges."""
    rows = rows.assign(kind=rows["start"].map(start_kind))
    out = []
    for (formulation, kind), g in rows.groupby(["formulation", "kind"], sort=False):
        taken = g[g["status"] != "skipped"]
        solved = taken[taken["status"] == "verified"]
        out.append({
            "formulation": formulation, "start": kind,
            "taken": len(taken), "solved": len(solved), "refused": len(g) - len(taken),
            "iterations": solved["iterations"].median() if len(solved) else float("nan"),
            "time_s": solved["time_s"].median() if len(solved) else float("nan"),
            "time_min_s": solved["time_min_s"].min() if len(solved) else float("nan"),
            "time_max_s": solved["time_max_s"].max() if len(solved) else float("nan"),
            "error_median": solved["fclib_error"].median() if len(solved) else float("nan"),
            "error_max": solved["fclib_error"].max() if len(solved) else float("nan"),
        })
    return pd.DataFrame(out)


def measure_table(rows, column):
    """problems x formulations of `column` for the cold solves, NaN where the solve failed;
    formulations that refused every problem are left out."""
    cold = rows[(rows["start"] == "cold") & (rows["status"] != "skipped")]
    if cold.empty:
        return pd.DataFrame()
    values = cold[column].where(cold["status"] == "verified")
    table = cold.assign(value=values).pivot_table(
        index="problem", columns="formulation", values="value", aggfunc="first", dropna=False)
    order = list(dict.fromkeys(cold["formulation"]))
    problems = list(dict.fromkeys(cold["problem"]))
    return table.reindex(index=problems, columns=order)


def plot_profiles(name, rows, path):
    """Time and iteration profiles of the cold solves over the problems; False when nothing
    was solved (no figure is written then)."""
    fig, axes = plt.subplots(1, 2, figsize=(15, 5.5))
    any_line = False
    formulations = list(dict.fromkeys(rows[rows["status"] != "skipped"]["formulation"]))
    colours = {f: plt.get_cmap("tab20")(i % 20) for i, f in enumerate(formulations)}
    for ax, column, what in ((axes[0], "time_s", "time"), (axes[1], "iterations", "iterations")):
        table = measure_table(rows, column)
        if table.empty:
            continue
        # A verified solve in 0 iterations (the start already solved it) has ratio 1, as the
        # best possible: the profile of iterations is over counts shifted by one.
        table = table + 1 if column == "iterations" else table
        ratios = aggregation.performance_ratios(table)
        finite = ratios.replace(np.inf, np.nan).max().max()
        top = max(2.0, float(finite) * 1.5) if finite == finite else 2.0
        taus = np.logspace(0, math.log10(top), 400)
        solved = table.notna().mean()
        for col, rho in aggregation.profile(ratios, taus).items():
            ax.step(taus, rho, where="post", color=colours[col], linewidth=1.8,
                    label=f"{col}: {solved[col]:.0%} solved")
            any_line = any_line or rho.max() > 0
        ax.set_xscale("log", base=2)
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel(f"tau (log2 scale): {what} at most tau x the best formulation's")
        ax.set_ylabel("fraction of problems solved within tau")
        ax.set_title(f"Performance profile of {what}" +
                     (" (+1)" if column == "iterations" else ""))
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=9, title="formulation (cold)")
    fig.suptitle(f"Dolan-More performance profiles over the problems of {name}, cold start")
    fig.tight_layout(rect=(0, 0, 0.75, 0.95))
    if any_line:
        fig.savefig(path, dpi=110)
    plt.close(fig)
    return any_line


def _time_text(row):
    if not row["solved"]:
        return "-"
    return "%s (%s - %s)" % tuple(aggregation.fmt(row[c] * 1e3) for c in
                                  ("time_s", "time_min_s", "time_max_s"))


def _opening(name, rows, run):
    """What the set is: its problems, what reading them changed, the settings of the solves."""
    problems = rows.drop_duplicates("problem")
    samples = rows[rows["status"] != "skipped"]["time_samples"]
    out = [f"### Problem set `{name}`", "",
           f"`{run.get('problem_source', 'contactbench compare --problem-dir')}`: "
           f"{len(problems)} problems, {rows['formulation'].nunique()} formulations, each "
           "problem solved once cold and once from each of its file's guesses, judged by the "
           f"verdict at tolerance {aggregation.fmt(rows['tolerance'].iloc[0])}, time limit "
           f"{aggregation.fmt(rows['time_limit_s'].iloc[0])} s per solve (0: none), "
           f"{int(samples.max()) if len(samples) else 0} timed solve(s) each.", ""]
    notes = run.get("problem_notes", [])
    dropped = [n for n in notes if "friction dropped" in n]
    if dropped:
        out += [f"Friction was dropped (mu set to 0) in {len(dropped)} of {len(problems)} "
                "problems (`--set friction=ignore`; run.json's `problem_notes`): these are "
                "frictionless problems made from frictional ones, and the files' own solutions "
                "are not their answers.", ""]
    out += ["| problem | d | nc | starts |", "|---|---|---|---|"]
    for _, p in problems.iterrows():
        starts = ", ".join(dict.fromkeys(rows[rows["problem"] == p["problem"]]["start"]))
        out.append(f"| {p['problem']} | {p['d']} | {p['nc']} | {starts} |")
    return out + [""]


def _unreadable(rows):
    """The files of the set that could not be read (status unreadable), with the reasons."""
    bad = rows[rows["status"] == "unreadable"]
    if bad.empty:
        return []
    out = [f"{len(bad)} file(s) of the set could not be read and were not solved "
           "(`problems.csv` status `unreadable`):", ""]
    for _, r in bad.iterrows():
        out.append(f"- `{os.path.basename(str(r['source']))}`: {r['message']}")
    return out + [""]


def set_section(name, all_rows, run, figures_dir):
    rows = all_rows[all_rows["status"] != "unreadable"]
    out = _opening(name, rows, run) + _unreadable(all_rows)
    table = summary_table(rows)
    out += ["Per formulation and start (`guess`: the solves from all the files' guesses): "
            "solves verified by the verdict of those it took, and the problems it refused; "
            "over the verified solves the median iterations, the median time in ms with the "
            "fastest and the slowest timed solve among them (a spread over problems and, with "
            "`--repeat`, repetitions), and the median and largest FCLIB error (natural-map "
            "residual relative to the data, `fclib_error`).", "",
            "| formulation | start | verified | refused | median iterations | time ms, median "
            "(fastest - slowest) | FCLIB error, median | largest |",
            "|---|---|---|---|---|---|---|---|"]
    for _, r in table[table["taken"] > 0].iterrows():
        out.append(f"| {r['formulation']} | {r['start']} | {r['solved']}/{r['taken']} | "
                   f"{r['refused']} | {aggregation.fmt(r['iterations'])} | {_time_text(r)} | "
                   f"{aggregation.fmt(r['error_median'])} | {aggregation.fmt(r['error_max'])} |")
    taken = table.groupby("formulation", sort=False)["taken"].sum()
    refused_all = list(taken[taken == 0].index)
    out.append("")
    if len(refused_all):
        out += ["Refused every problem (left out of the table and the profiles): " +
                ", ".join(refused_all) + ".", ""]
    figure = f"problem_set_{name.replace(os.sep, '_')}_profiles.png"
    if plot_profiles(name, rows, os.path.join(figures_dir, figure)):
        out += [f"![performance profiles of {name}](figures/comparison/{figure})", ""]
    else:
        out += ["No cold solve was verified: no performance profile.", ""]
    return out


def section(results_dir, figures_dir):
    """The markdown lines of the section, [] when there are no problem-set records."""
    sets = problem_sets(results_dir)
    if not sets:
        return []
    out = ["## Problem sets", "",
           "Collections of fixed-load problems (FCLIB files read as frictionless problems, "
           "docs/problem-files.md), every formulation on every problem "
           "(`contactbench compare --problem-dir`; docs/comparison.md \"Problem sets\"), as "
           "the FCLIB literature compares solvers (Acary, Bremond & Huber, INRIA RR-9118).", ""]
    for name, rows, run in sets:
        out += set_section(name, rows, run, figures_dir)
    return out
