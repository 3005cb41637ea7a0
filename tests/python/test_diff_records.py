"""scripts/diff_records.py --invariants on the committed records (results/block/eta1-newton, P1's
fixed-load solve, and results/arch-flat/newton, P2's path with its branch switch) against copies
edited the way a changed code would move them: it must catch a moved answer, a moved count and a
moved iteration histogram, and accept what only measures time or lies within the stated
tolerances. Run: /usr/bin/python3 -m unittest discover -s tests/python."""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "diff_records.py")
RUNS = {"p1": os.path.join(ROOT, "results", "block", "eta1-newton"),
        "p2": os.path.join(ROOT, "results", "arch-flat", "newton")}


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def write(path, header, rows):
    with open(path, "w", newline="") as f:
        csv.writer(f).writerows([header] + rows)


def edit_column(path, column, change, which=lambda i, row: True):
    """Rewrites column of the rows `which` selects (index, row) by change(text) -> text."""
    header, rows = read(path)
    c = header.index(column)
    for i, row in enumerate(rows):
        if which(i, row):
            row[c] = change(row[c])
    write(path, header, rows)


def scale(factor):
    return lambda text: repr(float(text) * factor)


@unittest.skipUnless(all(os.path.isdir(d) for d in RUNS.values()), "no committed records")
class DiffInvariants(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.old = os.path.join(self.tmp, "old")
        self.new = os.path.join(self.tmp, "new")
        for name, src in RUNS.items():
            for root in (self.old, self.new):
                os.makedirs(os.path.join(root, name))
                for f in os.listdir(src):  # the records, not the VTK files
                    if f.endswith(".csv") or f == "run.json":
                        shutil.copy(os.path.join(src, f), os.path.join(root, name, f))

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def path(self, run, name):
        return os.path.join(self.new, run, name)

    def diff(self):
        done = subprocess.run([sys.executable, SCRIPT, "--invariants", self.old, self.new],
                              capture_output=True, text=True)
        return done.returncode, done.stdout + done.stderr

    def assertCaught(self, *words):
        rc, out = self.diff()
        self.assertEqual(rc, 1, out)
        for w in words:
            self.assertIn(w, out)

    def assertAccepted(self):
        rc, out = self.diff()
        self.assertEqual(rc, 0, out)
        self.assertIn("2 runs agree", out)

    def test_identical_records_agree(self):
        self.assertAccepted()

    def test_a_timing_change_is_accepted(self):
        edit_column(self.path("p1", "steps.csv"), "time_s", scale(7.0))
        edit_column(self.path("p2", "steps.csv"), "time_s", scale(0.1))
        with open(self.path("p2", "run.json")) as f:
            info = json.load(f)
        info["wall_time_s"] *= 3.0
        info["started_at"] = "2099-01-01T00:00:00Z"
        with open(self.path("p2", "run.json"), "w") as f:
            json.dump(info, f)
        self.assertAccepted()

    def test_a_moved_answer_is_caught(self):
        # P1's displacements 1e-4 relative: beyond the 1e-6 of the answer.
        edit_column(self.path("p1", "solution.csv"), "uy", scale(1.0 + 1e-4))
        self.assertCaught("p1: answer differ")

    def test_an_answer_within_the_tolerance_is_accepted(self):
        edit_column(self.path("p1", "solution.csv"), "uy", scale(1.0 + 1e-9))
        self.assertAccepted()

    def test_a_moved_lambda_of_a_critical_point_is_caught(self):
        edit_column(self.path("p2", "critical.csv"), "lambda", scale(1.0 + 1e-4))
        self.assertCaught("p2: critical points differ")

    def test_a_moved_count_of_kinks_is_caught(self):
        header, rows = read(self.path("p2", "kinks.csv"))
        write(self.path("p2", "kinks.csv"), header, rows[:-1])
        self.assertCaught("p2: kinks differ", "%d vs %d" % (len(rows), len(rows) - 1))

    def test_a_moved_count_of_steps_is_caught(self):
        header, rows = read(self.path("p2", "steps.csv"))
        write(self.path("p2", "steps.csv"), header, rows[:-1])
        self.assertCaught("p2: ", "steps differ")

    def test_a_failed_branch_switch_is_caught(self):
        edit_column(self.path("p2", "steps.csv"), "branch_switch", lambda t: "false")
        self.assertCaught("p2: branches differ")

    def test_a_moved_histogram_is_caught_and_a_small_move_accepted(self):
        def one_more(first_steps):
            return lambda i, row: i < first_steps
        # 2000 steps: up to max(2, 1%) = 20 steps may take one iteration more.
        edit_column(self.path("p2", "steps.csv"), "iterations", lambda t: str(int(t) + 1),
                    one_more(20))
        self.assertAccepted()
        edit_column(self.path("p2", "steps.csv"), "iterations", lambda t: str(int(t) + 1),
                    lambda i, row: 20 <= i < 60)
        self.assertCaught("p2: iteration histogram", "of 2000 steps moved")

    def test_p1_iterations_within_one(self):
        edit_column(self.path("p1", "steps.csv"), "iterations", lambda t: str(int(t) + 1))
        self.assertAccepted()
        edit_column(self.path("p1", "steps.csv"), "iterations", lambda t: str(int(t) + 1))
        self.assertCaught("p1: iterations")

    def test_a_missing_run_is_caught(self):
        shutil.rmtree(os.path.join(self.new, "p1"))
        self.assertCaught("only in %s: p1" % self.old)


if __name__ == "__main__":
    unittest.main()
