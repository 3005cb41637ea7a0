"""The quick mode's reports (scripts/run_suite.sh --quick): with the marker in the results
directory REPORT.md and COMPARISON.md open with a line saying they are the quick mode's, with
the marker's text; without it they open with their titles. Run: /usr/bin/python3 -m unittest
discover -s tests/python."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results")
sys.path.insert(0, RESULTS)
from plotlib import quick  # noqa: E402


class QuickModeReports(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="contactbench_quick_")
        self.addCleanup(shutil.rmtree, self.dir)

    def reports(self):
        """plot.py on the (record-less) results directory; the first line of each report."""
        subprocess.run([sys.executable, os.path.join(RESULTS, "plot.py"), self.dir], check=True,
                       stderr=subprocess.DEVNULL)
        first = {}
        for name in ("REPORT.md", "COMPARISON.md"):
            with open(os.path.join(self.dir, name)) as f:
                first[name] = f.readline().rstrip("\n")
        return first

    def test_the_marker_makes_both_reports_say_so_first(self):
        with open(os.path.join(self.dir, quick.MARKER), "w") as f:
            f.write("the comparison sets on their first 100 steps;\nno benchmarks.\n")
        for name, line in self.reports().items():
            self.assertTrue(line.startswith("**Quick mode**"), f"{name}: {line}")
            self.assertTrue(line.endswith("the comparison sets on their first 100 steps; "
                                          "no benchmarks."), f"{name}: {line}")

    def test_without_the_marker_the_reports_open_with_their_titles(self):
        first = self.reports()
        self.assertEqual(first["REPORT.md"], "# Reproduction of the report's examples")
        self.assertEqual(first["COMPARISON.md"], "# Comparison of formulations")
        self.assertEqual(quick.opening(self.dir), [])


if __name__ == "__main__":
    unittest.main()
