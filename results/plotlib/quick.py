"""The quick mode of the main job (`scripts/run_suite.sh --quick`): shortened sets, made in a
few minutes to see the pipeline run and the shape of the results, not to quote them.

run_suite.sh marks such a results directory with the file MARKER, whose text says what was
shortened; the reports made from its records (REPORT.md, COMPARISON.md) then open with a line
saying they are the quick mode's, before anything else. A directory without the marker is a
full run's, and its reports open as they always did.
"""
import os

MARKER = "QUICK_MODE.txt"


def opening(results_dir):
    """The lines a report of `results_dir` opens with: the quick mode's line (and a blank line)
    when the marker is there, else none."""
    path = os.path.join(results_dir, MARKER)
    if not os.path.exists(path):
        return []
    with open(path) as f:
        what = " ".join(f.read().split())
    return ["**Quick mode** (`scripts/run_suite.sh --quick`): made from shortened sets, a first "
            "look and a check of the pipeline, not results to quote (those are the full run's, "
            "`scripts/run_suite.sh`). " + what, ""]
