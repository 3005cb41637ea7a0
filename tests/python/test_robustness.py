"""The step-size axis of results/plotlib/robustness.py on tiny hand-made records written the way
`contactbench compare` writes them (runs.csv, steps.csv), with answers worked out by hand.
Run: /usr/bin/python3 -m unittest discover -s tests/python (ctest: `python.comparison`)."""
import os
import sys
import tempfile
import unittest

import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results"))
from plotlib import comparison  # noqa: E402
from plotlib import robustness as rb  # noqa: E402


def write_run(root, problem, theta, accepted_x, iterations_x, accepted_y, cut_back=False):
    """One compare run at `theta`: formulation x (accepted / iterations per step), y (accepted,
    2 iterations each), z skipped; each replayed step carries its reference step's theta (the
    last one cut back to theta / 2 when `cut_back`), and a stray reference row is dropped."""
    d = os.path.join(root, "robustness", problem, f"theta-{theta}")
    os.makedirs(d)
    pd.DataFrame({
        "problem": [problem] * 3, "formulation": ["x", "y", "z"],
        "start": ["warm"] * 3, "mode": ["replay"] * 3,
        "status": ["converged", "failed", "skipped"],
        "message": ["", "", "z cannot express the step constraint 'arc-length'"],
    }).to_csv(os.path.join(d, "runs.csv"), index=False)
    n = len(accepted_x)
    reference_theta = [theta] * n
    if cut_back:
        reference_theta[-1] = theta / 2
    rows = []
    for k in range(n):
        rows.append(dict(problem=problem, formulation="implicit-fb", start="warm", step=k + 1,
                         iterations=3, accepted=True, mode="reference",
                         constraint="arc-length", arc_length=10 * theta))
        rows.append(dict(problem=problem, formulation="x", start="warm", step=k + 1,
                         iterations=iterations_x[k], accepted=accepted_x[k], mode="replay",
                         constraint="arc-length", arc_length=reference_theta[k]))
        rows.append(dict(problem=problem, formulation="y", start="warm", step=k + 1,
                         iterations=2, accepted=accepted_y[k], mode="replay",
                         constraint="arc-length", arc_length=reference_theta[k]))
    pd.DataFrame(rows).to_csv(os.path.join(d, "steps.csv"), index=False)


class Robustness(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = self.tmp.name
        # P3 first on disk order must not matter: sorted P2 before P3, theta ascending.
        write_run(root, "arch-curved", 1.0, [True, False], [9, 50], [False, False])
        write_run(root, "arch-flat", 1.0, [True, True], [4, 6], [True, False], cut_back=True)
        write_run(root, "arch-flat", 0.1, [True, True, True, True], [2, 3, 3, 4],
                  [True, True, True, True])

    def tearDown(self):
        self.tmp.cleanup()

    def test_runs_are_sorted_and_theta_is_the_nominal_one(self):
        found = rb.robustness_runs(self.tmp.name)
        self.assertEqual([(p, t) for p, t, *_ in found],
                         [("arch-flat", 0.1), ("arch-flat", 1.0), ("arch-curved", 1.0)])
        # Only replayed steps remain (the stray reference row's theta is not the run's).
        self.assertEqual(set(found[0][3]["mode"]), {"replay"})

    def test_success_and_iterations(self):
        table, skipped = rb.robustness_table(rb.robustness_runs(self.tmp.name))
        row = table.set_index(["problem", "theta", "formulation"])
        self.assertEqual(row.loc[("arch-flat", 0.1, "x"), "success"], 1.0)
        self.assertEqual(row.loc[("arch-flat", 0.1, "x"), "median_iterations"], 3.0)
        self.assertEqual(row.loc[("arch-flat", 0.1, "x"), "mean_iterations"], 3.0)
        self.assertEqual(row.loc[("arch-flat", 1.0, "y"), "success"], 0.5)
        # Iterations count accepted steps only: x's failed 50 on P3 is left out.
        self.assertEqual(row.loc[("arch-curved", 1.0, "x"), "median_iterations"], 9.0)
        self.assertEqual(row.loc[("arch-curved", 1.0, "y"), "solved"], 0)
        self.assertTrue(row.loc[("arch-curved", 1.0, "y"), "median_iterations"]
                        != row.loc[("arch-curved", 1.0, "y"), "median_iterations"])  # NaN
        self.assertNotIn("implicit-fb", set(table["formulation"]))
        self.assertIn(("arch-flat", "z"), skipped)

    def test_section_and_figure(self):
        figures = os.path.join(self.tmp.name, "figures", "comparison")
        os.makedirs(figures)
        text = "\n".join(rb.section(self.tmp.name, figures))
        self.assertIn("## Robustness against the step size", text)
        self.assertIn("### P2 arch-flat", text)
        self.assertIn("theta = 0.1 (4 steps)", text)
        self.assertIn("| x | 100% (4/4), 3 / 3 | 100% (2/2), 5 / 5 |", text)
        self.assertIn("Skipped: z - cannot express", text)  # one line, not a row per set
        self.assertTrue(os.path.exists(os.path.join(figures, "robustness_success.png")))

    def test_no_records_no_section(self):
        with tempfile.TemporaryDirectory() as empty:
            self.assertEqual(rb.section(empty, empty), [])

    def test_comparison_report_includes_the_section(self):
        comparison.write(self.tmp.name)
        with open(os.path.join(self.tmp.name, "COMPARISON.md")) as f:
            self.assertIn("## Robustness against the step size", f.read())


if __name__ == "__main__":
    unittest.main()
