#!/usr/bin/env python3
"""The one plotting script: figures and reports from the CSV/JSON records alone.

  /usr/bin/python3 results/plot.py [RESULTS_DIR]     (default: the directory of this script)

writes RESULTS_DIR/REPORT.md (the report's three examples, plotlib/reproduction.py, with the
readings study of plotlib/readings.py and the 3-D solids of plotlib/solid3d.py when the records
of scripts/run_readings.sh and scripts/run_solid3d.sh exist, and the commits and run times of
every part, plotlib/provenance.py) and
RESULTS_DIR/COMPARISON.md (the formulation comparison and the benchmarks,
plotlib/comparison.py), with their PNG figures under RESULTS_DIR/figures/. Records of the quick
mode (`scripts/run_suite.sh --quick`) come with its marker, RESULTS_DIR/QUICK_MODE.txt: both
reports then open with a line saying so (plotlib/quick.py). Needs Debian's
python3-matplotlib, python3-pandas and python3-numpy (hence /usr/bin/python3).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from plotlib import comparison, provenance, readings, reproduction, solid3d  # noqa: E402


def main(argv):
    results_dir = argv[1] if len(argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    sections = [readings.section(results_dir), solid3d.section(results_dir),
                provenance.section(results_dir)]
    reproduction.write(results_dir, [s for s in sections if s])
    print("wrote %s" % os.path.join(results_dir, "REPORT.md"), file=sys.stderr)
    comparison.write(results_dir)
    print("wrote %s" % os.path.join(results_dir, "COMPARISON.md"), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
