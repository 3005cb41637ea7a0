"""scripts/diff_comparison.py on the committed comparison set arch-flat-prefix (its 50 steps hold
converged and failed solves; a time-limited one is made by editing a copy) against copies edited
as a changed code or a slower machine would: a moved success count or median is caught, a moved
time and a time-limited solve that now succeeds are not, and a replay of the first steps
compares with the committed set's same steps.
Run: /usr/bin/python3 -m unittest discover -s tests/python."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import pandas as pd

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "diff_comparison.py")
SET = os.path.join(ROOT, "results", "compare", "arch-flat-prefix")


@unittest.skipUnless(os.path.isfile(os.path.join(SET, "steps.csv")), "no committed set")
class DiffComparison(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.tmp)
        for side in ("old", "new"):
            d = os.path.join(self.tmp, side, "compare", "arch-flat-prefix")
            os.makedirs(d)
            for f in ("runs.csv", "steps.csv"):
                shutil.copy(os.path.join(SET, f), d)
        self.steps_path = os.path.join(self.tmp, "new", "compare", "arch-flat-prefix",
                                       "steps.csv")
        self.steps = pd.read_csv(self.steps_path, dtype=str, keep_default_na=False)

    def save(self, steps):
        steps.to_csv(self.steps_path, index=False)

    def diff(self):
        done = subprocess.run([sys.executable, SCRIPT, os.path.join(self.tmp, "old"),
                               os.path.join(self.tmp, "new")], capture_output=True, text=True)
        return done.returncode, done.stdout + done.stderr

    def replayed(self, formulation, start, status=None):
        s = self.steps
        rows = (s["formulation"] == formulation) & (s["start"] == start) & \
            (s["mode"] == "replay")
        return rows & (s["status"] == status) if status else rows

    def test_the_same_records_agree(self):
        rc, out = self.diff()
        self.assertEqual(rc, 0, out)

    def test_times_are_not_compared(self):
        self.steps["time_s"] = (self.steps["time_s"].astype(float) * 9).map(repr)
        self.save(self.steps)
        rc, out = self.diff()
        self.assertEqual(rc, 0, out)

    def test_a_moved_median_is_caught(self):
        rows = self.replayed("implicit-fb", "warm")
        self.steps.loc[rows, "iterations"] = (self.steps.loc[rows, "iterations"].astype(int)
                                              + 1).map(str)
        self.save(self.steps)
        rc, out = self.diff()
        self.assertEqual(rc, 1, out)
        self.assertIn("implicit-fb warm: median iterations", out)

    def test_a_moved_success_count_is_caught(self):
        rows = self.replayed("implicit-fb", "warm")
        first = self.steps[rows].index[0]
        self.steps.loc[first, "accepted"] = "false"
        self.save(self.steps)
        rc, out = self.diff()
        self.assertEqual(rc, 1, out)
        self.assertIn("implicit-fb warm: verified 50 of 50 -> 49 of 50", out)

    def test_a_time_limited_solve_may_go_either_way(self):
        # A failed replayed solve made time-limited in the committed copy (the set need not
        # hold one: that depends on the machine) and verified in the new one.
        failed = self.steps[(self.steps["mode"] == "replay") & (self.steps["accepted"] == "false")]
        self.assertTrue(len(failed), "the set holds failed solves")
        first = failed.index[0]
        old = self.steps.copy()
        old.loc[first, "status"] = "time_limit"
        old.to_csv(os.path.join(self.tmp, "old", "compare", "arch-flat-prefix", "steps.csv"),
                   index=False)
        self.steps.loc[first, ["accepted", "status"]] = ["true", "converged"]
        self.save(self.steps)
        rc, out = self.diff()
        self.assertEqual(rc, 0, out)

    def test_a_solve_that_now_verifies_is_caught(self):
        # The same change without the time limit is a moved success count.
        failed = self.steps[(self.steps["mode"] == "replay") & (self.steps["accepted"] == "false")]
        self.steps.loc[failed.index[0], ["accepted", "status"]] = ["true", "converged"]
        self.save(self.steps)
        rc, out = self.diff()
        self.assertEqual(rc, 1, out)

    def test_a_short_replay_compares_with_the_same_steps(self):
        self.save(self.steps[self.steps["step"].astype(int) <= 20])
        rc, out = self.diff()
        self.assertEqual(rc, 0, out)


if __name__ == "__main__":
    unittest.main()
