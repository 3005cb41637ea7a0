#!/usr/bin/env python3
"""Figures of any one run or comparison: the path, the deformed shapes with the obstacles, the
cost per step, a step's residual history and, for a comparison, its profiles and histograms
(plotlib/run_plots.py says which figure shows what).

  /usr/bin/python3 results/plot_run.py OUT_DIR [--step N] [--figures DIR]

OUT_DIR is the --out directory of `contactbench run` or `contactbench compare`, of a named
problem or a problem file. The figures go to DIR (default OUT_DIR/figures); --step chooses the
step whose residual history is drawn (default: the one that took the most iterations). Needs
Debian's python3-matplotlib, python3-pandas and python3-numpy (hence /usr/bin/python3).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from plotlib import run_plots  # noqa: E402


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out_dir", metavar="OUT_DIR", help="a run's or comparison's --out")
    parser.add_argument("--step", type=int, help="the step of the residual history")
    parser.add_argument("--figures", metavar="DIR", help="where to write (OUT_DIR/figures)")
    args = parser.parse_args(argv[1:])
    figures = args.figures or os.path.join(args.out_dir, "figures")
    try:
        written = run_plots.write(args.out_dir, figures, step=args.step)
    except (FileNotFoundError, ValueError) as e:
        print(f"plot_run.py: {e}", file=sys.stderr)
        return 2
    except (OSError, KeyError, TypeError, IndexError) as e:
        # Records the figures do not expect (a file edited by hand, a column missing): a
        # sentence naming the directory, not a traceback.
        print(f"plot_run.py: {args.out_dir}: cannot plot these records ({type(e).__name__}: {e})",
              file=sys.stderr)
        return 3
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
