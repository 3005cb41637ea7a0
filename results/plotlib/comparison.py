"""The comparison report: RESULTS_DIR/COMPARISON.md and its figures, from the CSVs alone.

`write(results_dir)` reads only
  results_dir/compare/<set>/runs.csv, steps.csv   (`contactbench compare`, scripts/run_compare.sh)
  results_dir/bench/*.json                        (Google Benchmark JSON, scripts/run_bench.sh)
  results_dir/robustness/<problem>/<theta>/*.csv  (the step-size axis, plotlib/robustness.py)
  results_dir/compare/<set>/problems.csv          (problem sets, plotlib/problem_sets.py)
and writes results_dir/COMPARISON.md and PNG figures into results_dir/figures/comparison/.

Aggregation (docs/comparison.md "Aggregation"), per comparison set (one directory
of `compare`: one problem, the same replayed steps for every formulation x start):
  - success rate: accepted steps (verified by the verdict and not turned back) / steps;
  - shifted geometric means (shift 10) of time and iterations per step, a failed step charged
    at the run's time limit (runs.csv time_limit_s; without one, the largest time of the set)
    and at the largest iteration count of the set, normalised so that the best is 1.0;
  - Dolan-More performance profiles of time and iterations (a failed step has ratio infinity);
  - warm-start gain = cold / warm, of the shifted geometric means (failures charged) and of the
    medians over accepted steps;
  - iteration histograms of the accepted steps (the form of the report's Tables 1 and 2).
The scaling of the P1 cold solve (scaling_benchmark.json): time, iterations and memory against
d, and the growth exponent: the least-squares slope of log time against log d.
"""
import glob
import json
import math
import os
import platform
import re

import numpy as np
import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.patches import Patch  # noqa: E402

from plotlib import (  # noqa: E402
    headlines, histograms, problem_sets, quick, robustness, speed, styles)
# The shared pieces, named here too for the scripts and tests that read them as comparison.X.
from plotlib.aggregation import (  # noqa: E402,F401
    PROBLEM_LABEL, SHIFT, TIME_UNIT_MS, aggregate, charged, comparison_sets, fmt, growth_exponent,
    performance_ratios, profile, read_benchmarks, scaling_rows, shifted_geometric_mean,
    skipped_line, steps_of)

# The reference report's Table 2 (P3, BFGS quasi-Newton csolve, 1604 steps): steps per count.
REPORT_TABLE_2 = {3: 1081, 4: 379, 5: 100, 6: 6, 7: 7, 8: 10, 9: 9, 10: 10, 12: 2}
HISTOGRAM_MAX = 12  # histogram columns 0..12, then the ranges below (the NLPs' counts)
HISTOGRAM_RANGES = [(13, 20), (21, 50), (51, 100), (101, None)]


def time_range(row):
    """' (min-max)' of a benchmark row's repetitions, '' when it has none."""
    low, high = row.get("seconds_min", np.nan), row.get("seconds_max", np.nan)
    if not (np.isfinite(low) and np.isfinite(high)):
        return ""
    return f" ({fmt(low)}-{fmt(high)})"


def bench_load(context):
    """The load average (1 min) of a benchmark JSON's context at the start and, where
    scripts/run_bench.sh added it, the end."""
    start, end = context.get("load_avg"), context.get("load_avg_end")
    if not start:
        return "The load average was not recorded."
    text = f"Load average (1 min): {start[0]:.2f} at the start"
    return text + (f", {end[0]:.2f} at the end." if end else " (the end not recorded).")


def machine_lines(results_dir):
    """The machine, from the benchmark JSON context (where the timings were taken), else from
    this machine at generation time (said so)."""
    for path in sorted(glob.glob(os.path.join(results_dir, "bench", "*.json"))):
        try:
            ctx, _ = read_benchmarks(path)
        except (ValueError, OSError):
            continue
        if ctx:
            mhz = ctx.get("mhz_per_cpu")
            return [f"Machine (from the context of `bench/{os.path.basename(path)}`): "
                    f"{ctx.get('cpu_model', 'CPU model not recorded')}, "
                    f"{ctx.get('num_cpus', '?')} CPUs"
                    + (f" at {mhz} MHz" if mhz else "")
                    + f", host `{ctx.get('host_name', '?')}`, benchmarks run {ctx.get('date', '?')}"
                    + ". (The JSON's `library_build_type` is that of Debian's Google Benchmark "
                    "library, not of contactbench, which is built in Release.)"]
    model = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return [f"Machine (no benchmark JSON: read at report generation): {model}, "
            f"{os.cpu_count()} CPUs, {platform.system()} {platform.release()}."]


# --- aggregation of one comparison set ----------------------------------------------------

def solver_label(formulation, start):
    return f"{formulation} ({start})"


def set_title(name, runs, steps):
    problem = runs["problem"].iloc[0] if len(runs) else name
    n = steps["step"].nunique() if len(steps) else 0
    label = PROBLEM_LABEL.get(problem, problem)
    what = "1 fixed-load solve" if n == 1 else f"{n} replayed steps"
    return f"{label}, set `{name}` ({what})"


def timing_line(set_dir, steps):
    """How the set's times were taken: the repetitions of each solve, and the machine's load at
    the start and the end (run.json)."""
    samples = sorted(steps["time_samples"].unique()) if "time_samples" in steps else [1]
    if samples == [1]:
        how = "each solve timed once (a range is over the steps)"
    else:
        how = ("each solve timed " + "/".join(str(n) for n in samples)
               + " times (compare --repeat): its time is the median, the range is over the "
               "repetitions and the steps")
    load = "the load was not recorded (run.json before its load_average)"
    try:
        with open(os.path.join(set_dir, "run.json")) as f:
            averages = json.load(f).get("load_average") or {}
        start, end = averages.get("start"), averages.get("end")
        if start and end:
            load = (f"load average (1 min) {start['1min']:.2f} at the start, "
                    f"{end['1min']:.2f} at the end")
    except (OSError, ValueError):
        load = "no run.json: the load is unknown"
    return f"Times: {how}; {load}."


def warm_gain(table):
    """cold / warm per formulation with both starts."""
    rows = []
    for f, g in table.groupby("formulation", sort=False):
        w = g[g["start"] == "warm"]
        c = g[g["start"] == "cold"]
        if not len(w) or not len(c):
            continue
        w, c = w.iloc[0], c.iloc[0]
        div = lambda a, b: a / b if b and b == b and a == a else float("nan")  # noqa: E731
        if not w["solved"] or not c["solved"]:
            # With no solved step on one side the ratio would only restate the charges.
            why = "neither start solves a step" if not w["solved"] and not c["solved"] else (
                "warm solves no step" if not w["solved"] else "cold solves no step")
            rows.append(dict(formulation=f, why=why))
            continue
        rows.append(dict(formulation=f, why="",
                         sgm_time=div(c["sgm_time_ms"], w["sgm_time_ms"]),
                         sgm_iterations=div(c["sgm_iterations"], w["sgm_iterations"]),
                         median_time=div(c["median_time_ms"], w["median_time_ms"]),
                         median_iterations=div(c["median_iterations"], w["median_iterations"])))
    return pd.DataFrame(rows)


def measure_table(steps, runs, column):
    """Steps x solvers: the measure where the step was accepted, NaN where it failed."""
    ran = runs[runs["status"] != "skipped"]
    replay = steps[steps["mode"] == "replay"] if "mode" in steps else steps
    cols = {}
    for _, run in ran.iterrows():
        g = steps_of(replay, run["formulation"], run["start"])
        by_step = g.set_index("step")
        v = by_step[column].astype(float).where(by_step["accepted"].astype(bool))
        if column == "iterations":
            v = v.clip(lower=1)  # a step solved at its start counts as one iteration
        cols[solver_label(run["formulation"], run["start"])] = v
    return pd.DataFrame(cols)


def histogram(steps, formulation, start):
    g = steps_of(steps, formulation, start)
    acc = g[g["accepted"].astype(bool)]["iterations"].astype(int)
    counts = {k: int((acc == k).sum()) for k in range(0, HISTOGRAM_MAX + 1)}
    for lo, hi in HISTOGRAM_RANGES:
        counts[(lo, hi)] = int(((acc >= lo) & ((acc <= hi) if hi else True)).sum())
    counts["more"] = int((acc > HISTOGRAM_MAX).sum())
    counts["failed"] = int(len(g) - len(acc))
    return counts


# --- figures ------------------------------------------------------------------------------

STYLE = {"warm": "-", "cold": "--"}


def _colours(formulations):
    """The fixed colour of each formulation (plotlib/styles.py), the same in every figure."""
    return styles.colours(formulations)


def plot_profiles(name, title, runs, steps, path):
    """Time and iteration profiles side by side; False when nothing was solved."""
    fig, axes = plt.subplots(1, 2, figsize=(15, 5.5))
    formulations = list(dict.fromkeys(runs[runs["status"] != "skipped"]["formulation"]))
    colours = _colours(formulations)
    any_line = False
    for ax, column, what in ((axes[0], "time_s", "time per step"),
                             (axes[1], "iterations", "iterations per step")):
        table = measure_table(steps, runs, column)
        if table.empty:
            continue
        ratios = performance_ratios(table)
        finite = ratios.replace(np.inf, np.nan).max().max()
        top = max(2.0, float(finite) * 1.5) if finite == finite else 2.0
        taus = np.logspace(0, math.log10(top), 400)
        curves = profile(ratios, taus)
        solved = table.notna().mean()
        for col, rho in curves.items():
            f, start = col.rsplit(" (", 1)
            start = start.rstrip(")")
            ax.step(taus, rho, where="post", color=colours[f], linestyle=STYLE.get(start, ":"),
                    label=f"{col}: {solved[col]:.0%} solved", linewidth=1.8,
                    marker=styles.style(f)["marker"], markevery=(0.05, 0.2), markersize=5,
                    markerfacecolor=styles.style(f)["markerfacecolor"])
            any_line = any_line or rho.max() > 0
        ax.set_xscale("log", base=2)
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel(f"tau (log2 scale): {what} at most tau x the best formulation's")
        ax.set_ylabel("fraction of steps solved within tau")
        ax.set_title(f"Performance profile of {what}")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=9, title="formulation (start)")
    fig.suptitle(f"Dolan-More performance profiles: {title}")
    fig.tight_layout(rect=(0, 0, 0.75, 0.95))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return any_line


def histogram_bins(hi):
    """(low, high, label) bins of iteration counts up to hi: one per count up to 20, then
    doubling ranges (3-4, 5-8, ...) so that 2 and 100 iterations fit one readable axis."""
    if hi <= 20:
        return [(k, k, str(k)) for k in range(0, max(hi, 4) + 1)]
    bins = [(0, 0, "0"), (1, 1, "1"), (2, 2, "2")]
    lo = 3
    while lo <= hi:
        up = 2 * (lo - 1)
        bins.append((lo, up, f"{lo}-{up}"))
        lo = up + 1
    return bins


def histogram_figure(title, runs, steps, iteration_word):
    """One panel per formulation: accepted steps per iteration count, warm and cold bars side
    by side. Every panel has the same bins (those of the largest count of the figure: bins of
    several counts when it runs past 20) and the same kind of count axis, logarithmic when the
    small bins would vanish. None when no formulation ran."""
    ran = runs[runs["status"] != "skipped"]
    formulations = list(dict.fromkeys(ran["formulation"]))
    if not formulations:
        return None
    data, total = {}, {}
    for f, s in zip(ran["formulation"], ran["start"]):
        g = steps[(steps["formulation"] == f) & (steps["start"] == s)]
        total[f, s] = len(g)
        data[f, s] = g[g["accepted"].astype(bool)]["iterations"].astype(int).to_numpy()
    bins = histogram_bins(max([int(v.max()) for v in data.values() if len(v)], default=0))
    counts = {key: [int(((v >= lo) & (v <= up)).sum()) for lo, up, _ in bins]
              for key, v in data.items()}
    log = histograms.wants_log(list(counts.values()))
    cols = min(3, len(formulations))
    rows = math.ceil(len(formulations) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.8 * rows), squeeze=False)
    colour = {"warm": "tab:blue", "cold": "tab:orange"}
    x = np.arange(len(bins))
    for ax, f in zip(axes.flat, formulations):
        starts = list(ran[ran["formulation"] == f]["start"])
        ax.set_title(f)
        ax.set_xlabel(f"{iteration_word(f)} per step")
        if not any(len(data[f, s]) for s in starts):
            ax.text(0.5, 0.5, "no accepted step\n" + ", ".join(
                f"{s}: 0 of {total[f, s]}" for s in starts), ha="center", va="center",
                transform=ax.transAxes)
            ax.set_yticks([])
            ax.set_xticks([])
            continue
        with_data = [s for s in starts if len(data[f, s])]
        bar = 0.8 / len(with_data)
        handles = []
        for s in starts:
            c = colour.get(s, "tab:gray")
            handles.append(Patch(color=c, label=f"{s}: {len(data[f, s])} of {total[f, s]} "
                                 "accepted"))
            if len(data[f, s]):
                i = with_data.index(s)
                ax.bar(x + (i - (len(with_data) - 1) / 2) * bar, counts[f, s], width=bar,
                       color=c)
        histograms.label_bins(ax, x, [label for _, _, label in bins])
        histograms.count_axis(ax, "accepted steps", log)
        ax.legend(handles=handles, fontsize=8)
    for ax in list(axes.flat)[len(formulations):]:
        ax.axis("off")
    fig.suptitle(f"Iterations per accepted step: {title}")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return fig


def plot_histograms(title, runs, steps, path, iteration_word):
    """histogram_figure written to `path`; False when no formulation ran."""
    fig = histogram_figure(title, runs, steps, iteration_word)
    if fig is None:
        return False
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def plot_scaling(scaling, path):
    ok = scaling[~scaling["error_occurred"]]
    if ok.empty:
        return False
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    formulations = list(dict.fromkeys(scaling["formulation"]))
    for f in formulations:
        g = ok[ok["formulation"] == f].sort_values("d")
        if g.empty:
            continue
        k = growth_exponent(g["d"], g["seconds"])
        lab = f"{f} (slope {k:.2f})" if k == k else f
        axes[0].loglog(g["d"], g["seconds"], "-", label=lab, **styles.style(f))
        if "peak_rss_mb" in g:
            axes[1].loglog(g["d"], g["peak_rss_mb"], "-", label=f, **styles.style(f))
    axes[0].set_xlabel("d, degrees of freedom (P1 with n x n elements, d = 2 (n + 1)^2)")
    axes[0].set_ylabel("wall time of the cold solve [s]")
    axes[0].set_title("Time of one P1 cold solve (slope: fitted exponent of d)")
    axes[1].set_xlabel("d, degrees of freedom")
    axes[1].set_ylabel("peak resident memory during the solve [MB]")
    axes[1].set_title("Peak memory of one P1 cold solve")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=9)
    fig.suptitle("Scaling of the P1 block cold solve by formulation (scaling_benchmark)")
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


# --- Markdown -----------------------------------------------------------------------------

def iteration_word_for(runs):
    evaluations = set(runs[runs["settings"].astype(str).str.contains("iterations=evaluations")]
                      ["formulation"])
    return lambda f: "objective evaluations" if f in evaluations else "iterations"


def set_section(name, runs, steps, figures_dir, results_dir):
    title = set_title(name, runs, steps)
    table, skipped, time_charge, iter_charge = aggregate(runs, steps)
    out = [f"## {title}", ""]
    if table.empty:
        return out + ["No formulation ran on this set.", ""]
    word = iteration_word_for(runs)
    out += [timing_line(os.path.join(results_dir, "compare", name), steps), "",
            f"Failures charged at {fmt(time_charge)} s (the run's time limit per solve) and "
            f"{fmt(iter_charge, '.0f')} iterations (the largest count of the set). Shift 10 "
            "(times in ms). Ratios: this formulation's mean / the best mean of the set.", "",
            "| formulation | start | success | time SGM [ms] | time ratio | time ratio, "
            "unshifted GM | iterations SGM | iterations ratio | median time, accepted [ms] "
            "(range) | "
            "median iterations, accepted | total time [s] |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for _, r in table.iterrows():
        note = " (evaluations)" if word(r["formulation"]) != "iterations" else ""
        out.append(f"| {r['formulation']}{note} | {r['start']} | {r['success']:.0%} "
                   f"({r['solved']}/{r['steps']}) | {fmt(r['sgm_time_ms'])} | "
                   f"{fmt(r['sgm_time_ms_ratio'])} | {fmt(r['gm_time_ms_ratio'])} | "
                   f"{fmt(r['sgm_iterations'])} | {fmt(r['sgm_iterations_ratio'])} | "
                   f"{fmt(r['median_time_ms'])} ({fmt(r['min_time_ms'])}-"
                   f"{fmt(r['max_time_ms'])}) | {fmt(r['median_iterations'], 'g')} | "
                   f"{fmt(r['total_time_s'])} |")
    out.append("")
    out += skipped_line(skipped)

    gain = warm_gain(table)
    if len(gain):
        out += ["Warm-start gain (cold / warm): of the shifted geometric means with failures "
                "charged, and of the medians over accepted steps.", "",
                "| formulation | time (SGM) | iterations (SGM) | time (medians) | "
                "iterations (medians) |", "|---|---|---|---|---|"]
        for _, g in gain.iterrows():
            if g.get("why"):
                out.append(f"| {g['formulation']} | n/a: {g['why']} | | | |")
                continue
            out.append(f"| {g['formulation']} | {fmt(g['sgm_time'], '.2f')} | "
                       f"{fmt(g['sgm_iterations'], '.2f')} | {fmt(g['median_time'], '.2f')} | "
                       f"{fmt(g['median_iterations'], '.2f')} |")
        out.append("")

    n_steps = steps["step"].nunique()
    safe = name.replace("/", "_")
    if n_steps > 1:
        fig = os.path.join(figures_dir, f"profile_{safe}.png")
        if plot_profiles(name, title, runs, steps, fig):
            out += [f"![Performance profiles, {title}]({os.path.relpath(fig, results_dir)})", ""]
        else:
            os.remove(fig)
            out += ["No step of this set was solved: no performance profile.", ""]

    # Tables 1 and 2 of the reference report: accepted steps per iteration count.
    ran = runs[runs["status"] != "skipped"]
    cols = list(range(0, HISTOGRAM_MAX + 1)) + HISTOGRAM_RANGES
    head = [str(k) if isinstance(k, int) else (f"{k[0]}-{k[1]}" if k[1] else f"> {k[0] - 1}")
            for k in cols]
    out += ["Accepted steps per iteration count (the form of the report's Tables 1 and 2; "
            "NLopt rows count objective evaluations).", "",
            "| formulation | start | " + " | ".join(head) + " | failed |",
            "|---|---|" + "---|" * (len(cols) + 1)]
    for _, run in ran.iterrows():
        h = histogram(steps, run["formulation"], run["start"])
        out.append(f"| {run['formulation']} | {run['start']} | "
                   + " | ".join(str(h[k]) for k in cols) + f" | {h['failed']} |")
    if runs["problem"].iloc[0] == "arch-curved" and n_steps == 1604:
        out.append("| report Table 2 (BFGS, csolve), 1604 steps | | "
                   + " | ".join(str(REPORT_TABLE_2.get(k, 0)) if isinstance(k, int) else "0"
                                for k in cols) + " | |")
    out.append("")
    if n_steps > 1:
        fig = os.path.join(figures_dir, f"iterations_{safe}.png")
        if plot_histograms(title, runs, steps, fig, word):
            out += [f"![Iterations per step, {title}]({os.path.relpath(fig, results_dir)})", ""]
    return out


def scaling_section(results_dir, figures_dir):
    path = os.path.join(results_dir, "bench", "scaling_benchmark.json")
    if not os.path.exists(path):
        return ["## Scaling of the P1 cold solve", "", "No `bench/scaling_benchmark.json` "
                "(run `scripts/run_bench.sh`).", ""]
    context, bench = read_benchmarks(path)
    s = scaling_rows(bench)
    out = ["## Scaling of the P1 cold solve (`scaling_benchmark`)", "",
           "One fixed-load solve of P1 `block` from the cold start (g0 = -1, r0 = +1) by a fresh "
           "formulation (symbolic analysis included): wall time, the median of the repetitions "
           "where repeated (n >= 200, ipopt-mpcc at n = 100 and the NLopt runs: one solve). "
           "Growth exponent: least-squares slope of log time against log d over the verified "
           "sizes, of the wall time and of the process CPU time (the latter is less disturbed "
           "by other load on the machine). Memory: peak resident set during the solve, and "
           "below its increase over the resident set before it. A repeated time is the median "
           "with the range of the repetitions (min-max); a time without a range is one "
           "sample. " + bench_load(context), ""]
    if s.empty:
        return out + ["No scaling benchmark rows.", ""]
    ns = sorted(s["n"].unique())
    out += ["| formulation | " + " | ".join(f"n = {n} (d = {2 * (n + 1) ** 2})" for n in ns)
            + " | exponent of d (wall) | exponent of d (CPU) | fitted over n |",
            "|---|" + "---|" * (len(ns) + 3)]
    reasons = {}
    for f in dict.fromkeys(s["formulation"]):
        g = s[s["formulation"] == f]
        cells = []
        for n in ns:
            r = g[g["n"] == n]
            if r.empty:
                cells.append("")
                continue
            r = r.iloc[0]
            if r["error_occurred"]:
                msg = short_reason(str(r["error_message"]))
                reasons.setdefault(msg, len(reasons) + 1)
                cells.append(f"({reasons[msg]})")
            else:
                mem = r.get("peak_rss_mb", np.nan)
                cells.append(f"{fmt(r['seconds'])} s{time_range(r)}, "
                             f"{fmt(r.get('iterations'), '.0f')} it, "
                             f"{fmt(mem, '.0f')} MB")
        ok = g[~g["error_occurred"]]
        k = growth_exponent(ok["d"], ok["seconds"])
        k_cpu = growth_exponent(ok["d"], ok["cpu_seconds"])
        over = ", ".join(str(n) for n in sorted(ok["n"])) if len(ok) >= 2 else "-"
        out.append(f"| {f} | " + " | ".join(cells)
                   + f" | {fmt(k, '.2f')} | {fmt(k_cpu, '.2f')} | {over} |")
    out.append("")
    if reasons:
        out += ["Not timed:", ""]
        out += [f"- ({k}) {m}" for m, k in reasons.items()]
        out.append("")
    if "solve_mem_mb" in s:
        ok = s[~s["error_occurred"]]
        big = ok[ok["n"] == ok["n"].max()]
        if len(big):
            out += ["Memory added by the solve at the largest verified n: "
                    + "; ".join(f"{r['formulation']} {fmt(r['solve_mem_mb'], '.0f')} MB "
                                f"({fmt(r['solve_mem_mb'] * 1048576 / r['d'], '.0f')} "
                                "bytes per dof)"
                                for _, r in big.iterrows()) + ".", ""]
    fig = os.path.join(figures_dir, "scaling_block.png")
    if plot_scaling(s, fig):
        out += [f"![Scaling of the P1 cold solve]({os.path.relpath(fig, results_dir)})", ""]
    return out


def short_reason(message):
    """'not verified: eq .. comp .. (SOLVER MESSAGE, N iterations)' -> 'not verified: SOLVER
    MESSAGE' with the numbers dropped, so equal reasons group; other messages as they are."""
    m = re.match(r"^(.*?): eq .*? \((.*), \d+ iterations\)$", message)
    if not m:
        return message
    why = re.sub(r" at iteration \d+", "", m.group(2))
    why = re.sub(r"\(zero pivot in column \d+\)", "(zero pivot)", why)
    return f"{m.group(1)}: {why}"


def step_benchmark_section(results_dir):
    path = os.path.join(results_dir, "bench", "formulation_step_benchmark.json")
    if not os.path.exists(path):
        return []
    ctx, bench = read_benchmarks(path)
    b = bench[bench["run_name"].astype(str).str.startswith("FormulationStep/")].copy()
    if b.empty:
        return []
    parts = b["run_name"].str.split("/")
    b["problem"], b["formulation"], b["start"], b["label"] = (
        parts.str[1], parts.str[2], parts.str[3], parts.str[4])
    b["k"] = parts.str[5].str.replace("step:", "", regex=False)
    out = ["## One replayed step (`formulation_step_benchmark`)", "",
           "Google Benchmark timing of single replayed steps of the reference path (implicit-fb), "
           "each formulation starting from the same state with the same prediction (warm) or its "
           "fixed start (cold); median of the repetitions (nlopt-mpcc: one solve). A cell is "
           "time and iterations, or the reason it was not timed.", ""]
    reasons = {}
    for problem in dict.fromkeys(b["problem"]):
        g = b[b["problem"] == problem]
        where = ctx.get(f"{problem}_steps")
        labels = list(dict.fromkeys(zip(g["label"], g["k"])))
        heading = f"**{PROBLEM_LABEL.get(problem, problem)}**"
        if where:
            heading += f" (reference path: {where})"
        out += [heading, "",
                "| formulation | start | "
                + " | ".join(f"{lab}, step {k}" for lab, k in labels) + " |",
                "|---|---|" + "---|" * len(labels)]
        for (f, start), h in g.groupby(["formulation", "start"], sort=False):
            cells = []
            for lab, k in labels:
                r = h[(h["label"] == lab) & (h["k"] == k)]
                if r.empty:
                    cells.append("")
                    continue
                r = r.iloc[0]
                if r["error_occurred"]:
                    short = short_reason(str(r["error_message"]))
                    reasons.setdefault(short, len(reasons) + 1)
                    cells.append(f"({reasons[short]})")
                else:
                    cells.append(f"{fmt(r['seconds'] * 1e3)} ms, "
                                 f"{fmt(r.get('iterations'), '.0f')} it")
            out.append(f"| {f} | {start} | " + " | ".join(cells) + " |")
        out.append("")
    if reasons:
        out += ["Not timed (the benchmark's error message; details in the JSON):", ""]
        out += [f"- ({k}) {m}" for m, k in reasons.items()]
        out.append("")
    return out


# --- the targets of the implicit formulation (implicit_fb_benchmark.json) ---------

# Target bounds (docs/findings.md "Performance"): Newton, warm, eta case 1, the default
# linear solver.
TARGET_P1_N50_S = 0.1
TARGET_P3_STEP_S = 0.5e-3
TARGET_P3_PATH_S = 1.5
TARGET_MEDIAN_ITERATIONS = 3
TARGET_ITERATION_OVER_LU = 1.5
TARGET_P1_GROWTH = 1.3


def _bench_row(bench, run_name):
    r = bench[bench["run_name"].astype(str) == run_name]
    return None if r.empty or bool(r.iloc[0]["error_occurred"]) else r.iloc[0]


def target_rows(bench, solver="cholmod"):
    """(target, measured, met) for each target that `bench` (read_benchmarks of
    implicit_fb_benchmark.json) measures with `solver`: met is True or False, None where there
    is no bound (reported figures), and "not measured" (also the measured text) where the
    benchmark is missing or failed."""
    rows = []

    def add(target, row, text, met):
        if row is None:
            rows.append((target, "not measured", "not measured"))
        else:
            rows.append((target, text, bool(met)))

    r = _bench_row(bench, f"BM_BlockColdSolve/{solver}/50")
    add(f"P1 n = 50 cold solve < {TARGET_P1_N50_S} s", r,
        r is not None and f"{fmt(r['seconds'] * 1e3)} ms ({fmt(r.get('newton_iterations'), '.0f')} "
        "iterations)", r is not None and r["seconds"] < TARGET_P1_N50_S)
    for k in (100, 1000):
        r = _bench_row(bench, f"BM_ArchCurvedWarmStep/{solver}/{k}")
        add(f"one warm P3 step (after step {k}) < {TARGET_P3_STEP_S * 1e3} ms", r,
            r is not None and f"{fmt(r['seconds'] * 1e6)} us "
            f"({fmt(r.get('newton_iterations'), '.0f')} iterations)",
            r is not None and r["seconds"] < TARGET_P3_STEP_S)
    r = _bench_row(bench, f"BM_ArchPath/arch-curved/{solver}/iterations:3")
    add(f"whole P3 path (1604 steps, kinks located) < {TARGET_P3_PATH_S} s", r,
        r is not None and f"{fmt(r['seconds'])} s",
        r is not None and r["seconds"] < TARGET_P3_PATH_S)
    for problem in ("arch-flat", "arch-curved"):
        r = _bench_row(bench, f"BM_ArchPath/{problem}/{solver}/iterations:3")
        add(f"median Newton iterations per step, {PROBLEM_LABEL[problem]} <= "
            f"{TARGET_MEDIAN_ITERATIONS}", r,
            r is not None and f"{fmt(r.get('median_iterations'), '.0f')} "
            f"({fmt(r.get('steps'), '.0f')} steps)",
            r is not None and r.get("median_iterations") <= TARGET_MEDIAN_ITERATIONS)
    block_ratio = f"BM_IterationOverFactorizationBlock/{solver}"
    arch_ratio = f"BM_IterationOverFactorizationArchCurved/{solver}"
    for name, label in ((f"{block_ratio}/50", "P1 n = 50"),
                        (f"{block_ratio}/200", "P1 n = 200"),
                        (f"{arch_ratio}/100", "P3, step 100"),
                        (f"{arch_ratio}/1000", "P3, step 1000")):
        r = _bench_row(bench, name)
        unit, scale = ("ms", 1e3) if "Block" in name else ("us", 1e6)
        add(f"Newton iteration / KLU factorisation + solve of its Jacobian <= "
            f"{TARGET_ITERATION_OVER_LU}, {label}", r,
            r is not None and f"{fmt(r.get('per_newton_iteration_us') * 1e-6 * scale)} / "
            f"{fmt(r.get('lu_factorize_solve_us') * 1e-6 * scale)} {unit} = {fmt(r.get('ratio'))} "
            f"(kernel alone {fmt(r.get('kernel_ratio'))})",
            r is not None and r.get("ratio") <= TARGET_ITERATION_OVER_LU)
    block = bench[bench["run_name"].astype(str).str.match(rf"^BM_BlockColdSolve/{solver}/\d+$")
                  & ~bench["error_occurred"]].copy()
    if len(block) >= 2:
        block["n"] = block["run_name"].str.split("/").str[2].astype(int)
        block = block.sort_values("n")
        for lo in (block["n"].min(), 50):
            fit = block[block["n"] >= lo]
            if len(fit) < 2:
                continue
            k = growth_exponent(fit["d"], fit["seconds"])
            k_cpu = growth_exponent(fit["d"], fit["cpu_seconds"])
            rows.append((f"P1 time growth, n = {lo} to {fit['n'].max()}, <= d^{TARGET_P1_GROWTH}",
                         f"d^{fmt(k, '.2f')} (CPU time d^{fmt(k_cpu, '.2f')})",
                         k <= TARGET_P1_GROWTH))
        if "solve_peak_mb" in block:
            per_dof = block["solve_bytes_per_dof"] / 1024
            peaks = zip(block["n"], block["solve_peak_mb"], per_dof)
            rows.append(("peak memory of the P1 solve reported, linear in d",
                         "; ".join(f"n = {n}: {fmt(mb, '.0f')} MB ({fmt(b, '.2f')} kB per dof)"
                                   for n, mb, b in peaks),
                         None))
    else:
        rows.append((f"P1 time growth <= d^{TARGET_P1_GROWTH}", "not measured", "not measured"))
    return rows


def targets_section(results_dir):
    path = os.path.join(results_dir, "bench", "implicit_fb_benchmark.json")
    if not os.path.exists(path):
        return []
    _, bench = read_benchmarks(path)
    out = ["## Targets of the implicit formulation (`implicit_fb_benchmark`)", "",
           "Implicit smoothed FB, eta case 1, Newton, the default linear solver (`cholmod`: the "
           "condensed Cholesky, which hands systems with d < 1000, P2 and P3, to KLU); median of "
           "the repetitions, wall time. The comparator of the ratio is a KLU refactorisation with "
           "the previous pivot order and one solve of the same Jacobian (same pattern, same "
           "values); `kernel` is one iteration's Jacobian, factorisation, solve and residual "
           "alone, the ratio the whole solve divided by its iterations.", "",
           "| target | measured | met |", "|---|---|---|"]
    for target, measured, met in target_rows(bench):
        verdict = {None: "reported", True: "yes", False: "**no**"}.get(met, met)
        out.append(f"| {target} | {measured} | {verdict} |")
    out.append("")
    return out


def write(results_dir):
    """Writes results_dir/COMPARISON.md and results_dir/figures/comparison/*.png."""
    results_dir = os.path.abspath(results_dir)
    figures_dir = os.path.join(results_dir, "figures", "comparison")
    os.makedirs(figures_dir, exist_ok=True)
    out = ["# Comparison of formulations", "",
           "Generated by `results/plotlib/comparison.py` from the CSV records under `compare/` "
           "(`scripts/run_compare.sh`) and the Google Benchmark JSON under `bench/` "
           "(`scripts/run_bench.sh`). Protocol: `docs/comparison.md`; replay mode: "
           "every formulation x start solves the same steps of the reference path "
           "(implicit-fb), each from the reference's previous accepted state.", ""]
    out[:0] = quick.opening(results_dir)  # a quick run's report says so first
    out += machine_lines(results_dir)
    out += ["Absolute times are machine dependent; the ratios measured in one run are the "
            "figures to quote. For the NLopt formulations `iterations` counts objective "
            "evaluations (NLopt has no iteration counter).", ""]
    sets = list(comparison_sets(results_dir))
    out += headlines.section(results_dir, sets)
    if not sets:
        out += ["No comparison records under `compare/` (run `scripts/run_compare.sh`).", ""]
    for name, runs, steps in sets:
        out += set_section(name, runs, steps, figures_dir, results_dir)
    out += robustness.section(results_dir, figures_dir)
    out += problem_sets.section(results_dir, figures_dir)
    out += targets_section(results_dir)
    out += scaling_section(results_dir, figures_dir)
    out += speed.section(results_dir)
    out += step_benchmark_section(results_dir)
    path = os.path.join(results_dir, "COMPARISON.md")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    return path


if __name__ == "__main__":
    import sys
    print(write(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
