"""REPORT.md's P2 section and its figures say only what the records say about the branch switch.

The committed P2 records (results/arch-flat/newton: C located, the switch onto branch 1, the path
ending there) are edited into those of a run whose switch failed, as the path driver writes them:
the path truncated at C's step (the steps after the switch removed, so it ends on branch 0),
C's row of critical.csv not switched with the driver's failure message, the kinks and saved
states after C removed and C's state saved again as the final one. The generator
(results/plotlib/reproduction.py) must then say, in the text, the table and the figures' titles
and labels, that the switch failed and D is not reached; on the unedited records it must say the
switch happened and mark D. Run: /usr/bin/python3 -m unittest discover -s tests/python."""
import os
import shutil
import sys
import tempfile
import unittest
from unittest import mock

import pandas as pd

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results")
sys.path.insert(0, RESULTS)
from plotlib import reproduction  # noqa: E402

P2 = os.path.join(RESULTS, "arch-flat", "newton")
# The path driver's message when every attempt off C fails (ArcLengthTracer::AbandonBranchSwitch,
# src/path/arc_length_tracer.cc; critical.csv's message column).
FAILED = ("the branch switch failed: every attempt on the planes orthogonal to the null vector "
          "failed the verdict; the path goes on along its branch")


def copy_records(dest):
    os.makedirs(os.path.join(dest, "vtk"))
    for f in os.listdir(P2):
        if f.endswith(".csv") or f == "run.json":
            shutil.copy(os.path.join(P2, f), dest)
    for f in os.listdir(os.path.join(P2, "vtk")):
        if "obstacle" in f:
            shutil.copy(os.path.join(P2, "vtk", f), os.path.join(dest, "vtk"))


def fail_the_switch(run_dir):
    """Rewrites the records in run_dir as those of the same run whose switch at C failed."""
    def edit(name, change):
        path = os.path.join(run_dir, name)
        change(pd.read_csv(path, dtype=str, keep_default_na=False)).to_csv(path, index=False)

    critical = pd.read_csv(os.path.join(run_dir, "critical.csv"))
    c_step = int(critical[critical["kind"] == "bifurcation"]["step"].iloc[0])

    def no_switch(c):
        bif = c["kind"] == "bifurcation"
        c.loc[bif, "switched"] = "false"
        c.loc[bif, "message"] = FAILED
        return c

    def until_c(frame):
        return frame[frame["step"].astype(int) <= c_step]

    def c_saved_as_final(frame):
        kept = until_c(frame)
        kept = kept[kept["label"] != "final"]
        at_c = kept[(kept["step"].astype(int) == c_step) & (kept["label"] == "bifurcation")]
        return pd.concat([kept, at_c.assign(label="final")])

    edit("critical.csv", no_switch)
    for name in ("steps.csv", "kinks.csv", "iterations.csv"):
        edit(name, until_c)
    for name in ("snapshots.csv", "snapshot_contacts.csv"):
        edit(name, c_saved_as_final)
    return c_step


def texts(fig):
    """Every title, legend entry and annotation of a figure."""
    out = []
    for ax in fig.axes:
        out.append(ax.get_title())
        legend = ax.get_legend()
        if legend is not None:
            out += [t.get_text() for t in legend.get_texts()]
        out += [child.get_text() for child in ax.texts]
    return out


@unittest.skipUnless(os.path.isdir(P2), "no committed P2 records")
class FailedSwitchReport(unittest.TestCase):
    def report(self, edit):
        """(REPORT.md's text, {figure name: its texts}) of the P2 records, edited by `edit`."""
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        run_dir = os.path.join(tmp, "arch-flat", "newton")
        copy_records(run_dir)
        edit(run_dir)
        figures = {}
        save = reproduction._save

        def recording_save(fig, results_dir, name):
            figures[name] = texts(fig)
            return save(fig, results_dir, name)
        with mock.patch.object(reproduction, "_save", recording_save):
            reproduction.write(tmp)
        with open(os.path.join(tmp, "REPORT.md")) as f:
            return f.read(), figures

    def p2_section(self, report):
        start = report.index("## P2")
        return report[start:report.index("## P3")]

    def test_the_committed_records_say_the_switch_happened(self):
        # The control: on records where the switch succeeded, the same checks see it.
        report, figures = self.report(lambda run_dir: None)
        p2 = self.p2_section(report)
        self.assertIn("branch switched", p2)
        self.assertIn("after the switch at C", p2)
        self.assertNotIn("not reached", p2)
        self.assertIn("D", figures["p2_path.png"])  # the annotation
        self.assertTrue(any("D on branch 1" in t for t in figures["p2_path.png"]))
        self.assertTrue(any("at D (branch 1)" in t for t in figures["p2_deformed_last.png"]))

    def test_a_failed_switch_is_said_everywhere(self):
        steps = {}
        report, figures = self.report(lambda d: steps.setdefault("c", fail_the_switch(d)))
        p2 = self.p2_section(report)
        c_row = next(line for line in p2.splitlines() if line.startswith("| C,"))
        d_row = next(line for line in p2.splitlines() if line.startswith("| D,"))
        self.assertIn("step %d, not switched" % steps["c"], c_row)
        self.assertIn("not reached: no branch switch, the path ends on branch 0", d_row)
        self.assertIn("At C the branch switch did not happen (%s)" % FAILED, p2)
        self.assertIn("the bifurcation point was located but not left: " + FAILED, p2)
        self.assertIn("![P2 deformed at the last state]", p2)
        for claim in ("branch switched", "after the switch", "at D", "asymmetric branch D",
                      "branch 1"):
            self.assertNotIn(claim, p2.replace("| D, on the asymmetric branch |", ""))
        path_texts = figures["p2_path.png"]
        self.assertNotIn("D", path_texts)  # no state is marked D
        self.assertFalse(any("branch 1" in t or "after the switch" in t for t in path_texts))
        self.assertTrue(any("on branch 0 (D not reached: no switch)" in t for t in path_texts))
        deformed = figures["p2_deformed_last.png"]
        self.assertTrue(any("at the last state (branch 0; D not reached)" in t for t in deformed))
        self.assertFalse(any("at D" in t for t in deformed))


if __name__ == "__main__":
    unittest.main()
