"""Robustness against the step size: the section of COMPARISON.md and its figure.

Reads only results_dir/robustness/<problem>/<any name>/runs.csv and steps.csv, one
`contactbench compare` run (replay mode, warm start) per problem and arc length theta
(scripts/run_compare.sh, set `robustness`; docs/comparison.md "Robustness against the step
size"). Each run replays a reference path traced at its own theta over the same stretch of
arc length, so a larger theta means fewer, longer steps from a worse predictor. Per problem,
theta and formulation:
  - success rate: accepted steps / replayed steps (as aggregation.aggregate counts them);
  - the median and the mean iterations over the accepted steps;
and a figure of success against theta, one panel per problem.
"""
import glob
import os

import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
import matplotlib.ticker  # noqa: E402

from plotlib import aggregation, styles  # noqa: E402

ROOT = "robustness"


def nominal_theta(steps):
    """The run's theta: the largest arc length among its steps (each replayed step carries its
    reference step's theta, and the reference's cut-backs only shorten it)."""
    arc = steps[steps["constraint"] == "arc-length"]["arc_length"] if len(steps) else []
    return float(arc.max()) if len(arc) else float("nan")


def robustness_runs(results_dir):
    """(problem, theta, runs, steps) per run under results_dir/robustness, sorted by problem
    (the order of PROBLEM_LABEL) and theta; `steps` holds the replayed steps only."""
    found = []
    pattern = os.path.join(results_dir, ROOT, "**", "runs.csv")
    for runs_csv in glob.glob(pattern, recursive=True):
        steps_csv = os.path.join(os.path.dirname(runs_csv), "steps.csv")
        if not os.path.exists(steps_csv):
            continue
        runs = pd.read_csv(runs_csv)
        steps = pd.read_csv(steps_csv)
        if not len(runs):
            continue
        steps = steps[steps["mode"] == "replay"] if "mode" in steps else steps
        theta = nominal_theta(steps)
        found.append((runs["problem"].iloc[0], theta, runs, steps))
    order = list(aggregation.PROBLEM_LABEL)

    def key(item):
        problem, theta = item[0], item[1]
        return (order.index(problem) if problem in order else len(order), problem, theta)

    return sorted(found, key=key)


def robustness_table(found):
    """One row per problem x theta x formulation that ran: steps, solved, success, median and
    mean iterations over accepted steps. Returns (table, skipped) where skipped maps
    (problem, formulation) to the reason a formulation did not run."""
    rows, skipped = [], {}
    for problem, theta, runs, steps in found:
        for _, run in runs.iterrows():
            if run["status"] == "skipped":
                skipped[(problem, run["formulation"])] = run["message"]
                continue
            g = aggregation.steps_of(steps, run["formulation"], run["start"])
            ok = g["accepted"].astype(bool)
            acc = g[ok]["iterations"]
            rows.append(dict(problem=problem, theta=theta, formulation=run["formulation"],
                             start=run["start"], steps=len(g), solved=int(ok.sum()),
                             success=ok.mean() if len(g) else float("nan"),
                             median_iterations=acc.median() if len(acc) else float("nan"),
                             mean_iterations=acc.mean() if len(acc) else float("nan")))
    return pd.DataFrame(rows), skipped


def plot_success(table, path):
    """The failed steps against theta (both on log scales: 0 failures at the bottom, on the
    linear stretch of a symlog axis), a panel per problem, a line per formulation in its fixed
    style. Success fractions all near 100 % looked alike on a 0-1 axis; the failure counts
    separate the formulations."""
    problems = list(dict.fromkeys(table["problem"]))
    fig, axes = plt.subplots(1, len(problems), figsize=(6.5 * len(problems), 4.8), squeeze=False)
    for ax, problem in zip(axes.flat, problems):
        t = table[table["problem"] == problem]
        groups = list(t.groupby("formulation", sort=False))
        for k, (f, g) in enumerate(groups):
            g = g.sort_values("theta")
            # Each formulation a little apart along theta, so that equal counts (0) stay seen.
            nudge = 1.0 + 0.03 * (k - (len(groups) - 1) / 2)
            ax.plot(g["theta"] * nudge, g["steps"] - g["solved"], "-", label=f,
                    **styles.style(f))
        most = float((t["steps"] - t["solved"]).max())
        thetas = sorted(t["theta"].unique())
        ax.set_xscale("log")
        ax.set_xticks(thetas, [f"{x:g}" for x in thetas])
        ax.minorticks_off()
        ax.set_yscale("symlog", linthresh=1)
        ax.set_ylim(-0.3, max(2.0, 1.5 * most))
        ticks = [v for v in (0, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000)
                 if v <= max(2.0, 1.5 * most)]
        ax.set_yticks(ticks, [str(v) for v in ticks])
        ax.yaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        ax.set_xlabel("arc length theta (log scale)")
        ax.set_ylabel("failed steps of the warm replay (symlog scale)")
        ax.set_title(aggregation.PROBLEM_LABEL.get(problem, problem))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Robustness against the step size: steps the warm replay failed "
                 "(0 at the bottom)")
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def section(results_dir, figures_dir):
    """The markdown lines of the section (empty when there are no robustness records)."""
    found = robustness_runs(results_dir)
    if not found:
        return []
    table, skipped = robustness_table(found)
    out = ["## Robustness against the step size", "",
           "P2 and P3 replayed at several arc lengths theta, each theta a reference path of its "
           "own (implicit-fb) over the same stretch of arc length, warm start "
           "(`scripts/run_compare.sh robustness`; docs/comparison.md). A larger theta gives "
           "fewer, longer steps and a worse predictor. Success: accepted / replayed steps; "
           "iterations over the accepted steps.", ""]
    if table.empty:
        return out + ["No formulation ran on these sets.", ""]
    for problem, t in table.groupby("problem", sort=False):
        thetas = sorted(t["theta"].unique())
        steps = {th: int(t[t["theta"] == th]["steps"].max()) for th in thetas}
        out += [f"### {aggregation.PROBLEM_LABEL.get(problem, problem)}", "",
                "| formulation | " + " | ".join(
                    f"theta = {th:g} ({steps[th]} steps): success, median / mean iterations"
                    for th in thetas) + " |",
                "|---|" + "---|" * len(thetas)]
        for f, g in t.groupby("formulation", sort=False):
            cells = []
            for th in thetas:
                r = g[g["theta"] == th]
                if not len(r):
                    cells.append("-")
                    continue
                r = r.iloc[0]
                cells.append(f"{r['success']:.0%} ({r['solved']}/{r['steps']}), "
                             f"{aggregation.fmt(r['median_iterations'], 'g')} / "
                             f"{aggregation.fmt(r['mean_iterations'], '.3g')}")
            out.append(f"| {f} | " + " | ".join(cells) + " |")
        out.append("")
        out += aggregation.skipped_line(pd.DataFrame(
            [dict(formulation=f, message=why) for (p, f), why in skipped.items() if p == problem],
            columns=["formulation", "message"]))
    path = os.path.join(figures_dir, "robustness_success.png")
    plot_success(table, path)
    out += [f"![Failed steps against theta]({os.path.relpath(path, results_dir)})", ""]
    return out
