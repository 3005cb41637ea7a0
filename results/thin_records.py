#!/usr/bin/env python3
"""Thins a study's records in place to what REPORT.md's section reads, so that they can be
committed and results/plot.py on a fresh clone writes the same section:
  readings   the readings study (plotlib/readings.py, thin_run): about 66 MB to 8;
  solid3d    the 3-D solids (plotlib/solid3d.py, thin_records): about 25 MB to 1.
scripts/run_readings.sh and scripts/run_solid3d.sh call it last (KEEP_FULL=1 skips it).

  /usr/bin/python3 results/thin_records.py RESULTS_DIR readings|solid3d
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from plotlib import readings, solid3d  # noqa: E402

PARTS = {"readings": readings.thin_records, "solid3d": solid3d.thin_records}


def main(argv):
    if len(argv) != 3 or argv[2] not in PARTS or not os.path.isdir(
            os.path.join(argv[1], argv[2])):
        print("usage: results/thin_records.py RESULTS_DIR readings|solid3d (with "
              "RESULTS_DIR/readings/ or RESULTS_DIR/solid3d/)", file=sys.stderr)
        return 2
    PARTS[argv[2]](argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
