"""What the comparison report's sections share: the records of the comparison sets and of the
Google Benchmark JSON as read, the aggregation maths (docs/comparison.md "Aggregation"), the
problems' labels and the number format. comparison.py, headlines.py, robustness.py and
problem_sets.py import it; it imports none of them (no import circle).
"""
import glob
import json
import math
import os

import numpy as np
import pandas as pd

SHIFT = 10.0
# Times enter the shifted means in milliseconds, so the shift is 10 ms. The shifted mean lies
# between the geometric mean (values far above the shift) and the arithmetic mean (values far
# below it): with 10 s, the convention for solves of seconds to hours, every per-step mean here
# (0.05 ms ... 5 s) would be nearly arithmetic and dominated by the failures charged at the
# time limit. The unshifted geometric-mean ratio is reported beside it.
TIME_UNIT_MS = 1e3
PROBLEM_LABEL = {"block": "P1 block", "arch-flat": "P2 arch-flat", "arch-curved": "P3 arch-curved"}


# --- the aggregation maths (unit-tested in tests/python/test_comparison.py) -----------------

def shifted_geometric_mean(values, shift=SHIFT):
    """exp(mean(log(x + shift))) - shift, over finite non-negative values."""
    x = np.asarray(values, dtype=float)
    if x.size == 0:
        return float("nan")
    if np.any(x < 0) or not np.all(np.isfinite(x)):
        raise ValueError("shifted geometric mean needs finite non-negative values")
    return float(np.exp(np.mean(np.log(x + shift))) - shift)


def charged(values, solved, charge):
    """The values with every unsolved entry replaced by `charge` (failures at the limit)."""
    v = np.asarray(values, dtype=float).copy()
    v[~np.asarray(solved, dtype=bool)] = charge
    return v


def performance_ratios(table):
    """Dolan-More ratios: `table` is a DataFrame problems x solvers with the measure of each
    solved pair and NaN (or inf) for a failure. r[p, s] = t[p, s] / min_s t[p, s]; inf where s
    failed or no solver solved p."""
    t = table.astype(float).replace([np.inf], np.nan)
    best = t.min(axis=1, skipna=True)
    ratios = t.div(best, axis=0)
    return ratios.fillna(np.inf)


def profile(ratios, taus):
    """rho_s(tau) = fraction of problems with r[p, s] <= tau, for each solver (column)."""
    r = np.asarray(ratios, dtype=float)
    taus = np.asarray(taus, dtype=float)
    return {col: np.array([(r[:, j] <= tau).mean() for tau in taus])
            for j, col in enumerate(ratios.columns)}


def growth_exponent(d, t):
    """Least-squares slope of log t against log d (t ~ d^slope); NaN with fewer than 2 points."""
    d = np.asarray(d, dtype=float)
    t = np.asarray(t, dtype=float)
    ok = np.isfinite(d) & np.isfinite(t) & (d > 0) & (t > 0)
    if ok.sum() < 2:
        return float("nan")
    slope, _ = np.polyfit(np.log(d[ok]), np.log(t[ok]), 1)
    return float(slope)


# --- reading ------------------------------------------------------------------------------

def comparison_sets(results_dir):
    """(name, runs, steps) per `compare` output directory under results_dir/compare."""
    root = os.path.join(results_dir, "compare")
    # The order of scripts/run_compare.sh (full paths, prefixes, P1), then any other set.
    order = ["arch-flat", "arch-curved", "arch-flat-prefix", "arch-curved-prefix", "block"]

    def key(path):
        name = os.path.relpath(os.path.dirname(path), root)
        return (order.index(name) if name in order else len(order), name)

    for runs_csv in sorted(glob.glob(os.path.join(root, "**", "runs.csv"), recursive=True),
                           key=key):
        d = os.path.dirname(runs_csv)
        steps_csv = os.path.join(d, "steps.csv")
        if not os.path.exists(steps_csv):
            continue
        runs = pd.read_csv(runs_csv)
        steps = pd.read_csv(steps_csv)
        steps = steps[steps["mode"] != "reference"]
        yield os.path.relpath(d, root), runs, steps


def read_benchmarks(path):
    """Google Benchmark JSON -> (context dict, DataFrame with one row per benchmark: the median
    aggregate where repetitions were aggregated, else the single run; errors kept)."""
    with open(path) as f:
        data = json.load(f)
    rows = []
    for b in data.get("benchmarks", []):
        rows.append(b)
    df = pd.DataFrame(rows)
    if df.empty:
        return data.get("context", {}), df
    if "run_name" not in df:
        df["run_name"] = df["name"]
    for col in ("aggregate_name", "error_occurred", "error_message"):
        if col not in df:
            df[col] = np.nan
    df["error_occurred"] = df["error_occurred"].fillna(False).astype(bool)
    picked = []
    for run_name, g in df.groupby("run_name", sort=False):
        errors = g[g["error_occurred"]]
        if len(errors):
            picked.append(errors.iloc[0])
            continue
        median = g[g["aggregate_name"] == "median"]
        row = (median.iloc[0] if len(median) else g.iloc[0]).copy()
        # The range of the repetitions (the min and max statistics every binary adds); none for
        # a single run or a JSON from before they were added.
        for bound in ("min", "max"):
            b = g[g["aggregate_name"] == bound]
            row[f"real_time_{bound}"] = b.iloc[0]["real_time"] if len(b) else np.nan
        picked.append(row)
    out = pd.DataFrame(picked).reset_index(drop=True)
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    for column, src in (("seconds", "real_time"), ("cpu_seconds", "cpu_time"),
                        ("seconds_min", "real_time_min"), ("seconds_max", "real_time_max")):
        out[column] = [v * scale.get(u, 1.0) if isinstance(u, str) else np.nan
                       for v, u in zip(out.get(src, np.nan), out.get("time_unit", ""))]
    return data.get("context", {}), out


def steps_of(steps, formulation, start):
    """The step records of one run (formulation x start)."""
    return steps[(steps["formulation"] == formulation) & (steps["start"] == start)]


def _time_bound(steps, column, pick):
    """The fastest (pick=min) or slowest (max) solve time of `steps`: over their repetitions
    (time_min_s, time_max_s of `compare --repeat`) where recorded, else over time_s."""
    if not len(steps):
        return float("nan")
    values = steps[column] if column in steps else steps["time_s"]
    return float(pick(values))


def aggregate(runs, steps):
    """Per formulation x start that ran: counts, success rate, shifted geometric means with
    failures charged, medians over accepted steps. Returns (table, skipped runs)."""
    skipped = runs[runs["status"] == "skipped"]
    ran = runs[runs["status"] != "skipped"]
    limit = float(runs["time_limit_s"].max()) if "time_limit_s" in runs else 0.0
    replay = steps[steps["mode"] == "replay"] if "mode" in steps else steps
    time_charge = limit if limit > 0 else float(replay["time_s"].max())
    iter_charge = float(replay["iterations"].max()) if len(replay) else 0.0
    rows = []
    for _, run in ran.iterrows():
        g = steps_of(replay, run["formulation"], run["start"])
        ok = g["accepted"].astype(bool).to_numpy()
        t_ms = charged(g["time_s"].to_numpy(), ok, time_charge) * TIME_UNIT_MS
        its = charged(g["iterations"].to_numpy(), ok, iter_charge)
        acc = g[ok]
        rows.append(dict(
            formulation=run["formulation"], start=run["start"], steps=len(g), solved=int(ok.sum()),
            success=ok.mean() if len(g) else float("nan"),
            sgm_time_ms=shifted_geometric_mean(t_ms) if len(g) else float("nan"),
            gm_time_ms=shifted_geometric_mean(t_ms, 0.0) if len(g) else float("nan"),
            sgm_iterations=shifted_geometric_mean(its) if len(g) else float("nan"),
            median_time_ms=acc["time_s"].median() * TIME_UNIT_MS if len(acc) else float("nan"),
            min_time_ms=_time_bound(acc, "time_min_s", min) * TIME_UNIT_MS,
            max_time_ms=_time_bound(acc, "time_max_s", max) * TIME_UNIT_MS,
            median_iterations=acc["iterations"].median() if len(acc) else float("nan"),
            total_time_s=g["time_s"].sum()))
    table = pd.DataFrame(rows)
    if len(table):
        for col in ("sgm_time_ms", "gm_time_ms", "sgm_iterations"):
            table[col + "_ratio"] = table[col] / table[col].min()
    return table, skipped, time_charge, iter_charge


def fmt(v, spec=".3g"):
    if v is None or (isinstance(v, float) and (math.isnan(v) or math.isinf(v))):
        return "-"
    return format(v, spec)


def scaling_rows(bench):
    """Rows of scaling_benchmark (BlockColdSolve/<formulation>/n:<n>)."""
    s = bench[bench["run_name"].astype(str).str.startswith("BlockColdSolve/")].copy()
    if s.empty:
        return s
    parts = s["run_name"].str.split("/")
    s["formulation"] = parts.str[1]
    s["n"] = parts.str[2].str.replace("n:", "", regex=False).astype(int)
    if "d" not in s:
        s["d"] = np.nan
    s["d"] = s["d"].fillna(2 * (s["n"] + 1) ** 2)
    return s


def skipped_line(skipped):
    """The skipped runs of a set as one line below its table: the formulations (starts
    merged) with, for each distinct reason, the reason once (the formulation's own name in it
    written as "it"), instead of a table row per formulation x start repeating it."""
    if skipped is None or not len(skipped):
        return []
    by_reason = {}
    for f, g in skipped.groupby("formulation", sort=False):
        message = str(g["message"].iloc[0])
        reason = message.replace(f + " ", "", 1) if message.startswith(f + " ") else message
        by_reason.setdefault(reason, []).append(f)
    parts = [f"{', '.join(fs)} - {reason}" for reason, fs in by_reason.items()]
    return ["Skipped: " + "; ".join(parts) + ".", ""]
