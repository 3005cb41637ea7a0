"""Where the records come from: the section "The records: commits and run times" of
RESULTS_DIR/REPORT.md, one table that results/README.md links to instead of typing commits and
run times by hand.

`section(results_dir)` reads every run.json under the parts of the main job (the report's
examples, the readings, the 3-D solids, each comparison set, each step-size set) and the context
of each benchmark JSON, and gives per part: the runs, the commit(s) of the binary that made them
(run.json's `commit`), when the first started, and the sum of the runs' wall times (run.json's
`wall_time_s`: the solves and their records, not the scripts around them). The benchmarks record
their start and the load average, not their run time.
"""
import glob
import json
import os

# (label, the part's directories under results_dir), in the main job's order.
PARTS = [("the report's examples (`scripts/run_suite.sh`)", ("block", "arch-flat", "arch-curved")),
         ("the readings (`scripts/run_readings.sh`)", ("readings",)),
         ("the 3-D solids (`scripts/run_solid3d.sh`)", ("solid3d",))]


def _runs(results_dir, dirs):
    out = []
    for d in dirs:
        for path in sorted(glob.glob(os.path.join(results_dir, d, "**", "run.json"),
                                     recursive=True)):
            with open(path) as f:
                out.append(json.load(f))
    return out


def _commits(runs):
    return ", ".join(sorted({r.get("commit", "?")[:7] + ("-dirty" if r.get("commit", "")
                                                         .endswith("-dirty") else "")
                             for r in runs}))


def _row(label, runs):
    started = min(r.get("started_at", "?") for r in runs)
    seconds = sum(float(r.get("wall_time_s") or 0.0) for r in runs)
    return "| %s | %d | %s | %s | %.0f s |" % (label, len(runs), _commits(runs), started, seconds)


def _parts(results_dir):
    parts = list(PARTS)
    for kind, root in (("comparison set", "compare"), ("step-size set", "robustness")):
        for path in sorted(glob.glob(os.path.join(results_dir, root, "*"))):
            if os.path.isdir(path):
                name = os.path.relpath(path, results_dir)
                parts.append(("%s `%s` (`scripts/run_compare.sh`)" % (kind, name), (name,)))
    return parts


def _benchmarks(results_dir):
    out = []
    for path in sorted(glob.glob(os.path.join(results_dir, "bench", "*.json"))):
        try:
            with open(path) as f:
                context = json.load(f).get("context", {})
        except ValueError:
            continue
        load, end = context.get("load_avg"), context.get("load_avg_end")
        commit = context.get("contactbench_commit")
        wall = context.get("wall_time_s")
        out.append("| benchmark `%s` (`scripts/run_bench.sh`) | - | %s | %s | %s%s%s |" % (
            os.path.basename(path), commit[:7] if commit else "(not recorded)",
            context.get("date", "?"), "%d s" % wall if wall is not None else "not recorded",
            "; load average at the start %s" % ", ".join("%.1f" % x for x in load)
            if load else "",
            ", at the end %s" % ", ".join("%.1f" % x for x in end) if end else ""))
    return out


def section(results_dir):
    """The REPORT.md section, or None when no part has records."""
    rows = []
    for label, dirs in _parts(results_dir):
        runs = _runs(results_dir, dirs)
        if runs:
            rows.append(_row(label, runs))
    rows += _benchmarks(results_dir)
    if not rows:
        return None
    return ["## The records: commits and run times", "",
            "Each part of the main job (`bash scripts/run_suite.sh`) as its records say: the "
            "runs (one run.json each), the commit of the binary that made them, when the first "
            "started (UTC) and the sum of their wall times (the runs, not the scripts around "
            "them; on the machine and under the load of that run).", "",
            "| part | runs | commit | started | wall time |", "|---|---|---|---|---|"] + rows + [""]
