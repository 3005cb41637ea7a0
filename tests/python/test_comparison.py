"""The aggregation maths of results/plotlib/comparison.py on small hand-made tables whose
answers are worked out by hand. Run: /usr/bin/python3 -m unittest discover -s tests/python
(ctest runs it as `python.comparison`)."""
import json
import math
import os
import sys
import tempfile
import unittest

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results"))
from plotlib import comparison as c  # noqa: E402


class ShiftedGeometricMean(unittest.TestCase):
    def test_hand_computed(self):
        # (0 + 10)(10 + 10)(90 + 10) = 20000; its cube root minus the shift.
        self.assertAlmostEqual(c.shifted_geometric_mean([0, 10, 90], 10), 20000 ** (1 / 3) - 10)

    def test_shift_zero_is_the_geometric_mean(self):
        self.assertAlmostEqual(c.shifted_geometric_mean([1, 4, 16], 0), 4.0)

    def test_constant_values_are_their_own_mean_for_any_shift(self):
        for shift in (0, 1, 10, 1e3):
            self.assertAlmostEqual(c.shifted_geometric_mean([7, 7, 7], shift), 7.0)

    def test_lies_between_the_geometric_and_the_arithmetic_mean(self):
        # log(x + s) is nearly linear for x << s: the shift moves the mean from the geometric
        # (s = 0) towards the arithmetic one, so a few tiny values do not dominate it.
        x = [0.1, 10.0]
        self.assertAlmostEqual(c.shifted_geometric_mean(x, 10), math.sqrt(10.1 * 20) - 10)
        self.assertLess(c.shifted_geometric_mean(x, 0), c.shifted_geometric_mean(x, 10))
        self.assertLess(c.shifted_geometric_mean(x, 10), c.shifted_geometric_mean(x, 1e6))
        self.assertAlmostEqual(c.shifted_geometric_mean(x, 1e9), np.mean(x), places=4)

    def test_refuses_negative_or_infinite(self):
        with self.assertRaises(ValueError):
            c.shifted_geometric_mean([1, -1])
        with self.assertRaises(ValueError):
            c.shifted_geometric_mean([1, math.inf])

    def test_failures_are_charged(self):
        np.testing.assert_array_equal(c.charged([1, 2, 3], [True, False, True], 5), [1, 5, 3])


class PerformanceProfile(unittest.TestCase):
    def setUp(self):
        # Three problems, two solvers; A fails problem 3, nobody solves problem 4.
        self.table = pd.DataFrame({"A": [1.0, 2.0, np.nan, np.nan], "B": [2.0, 2.0, 3.0, np.nan]},
                                  index=[1, 2, 3, 4])

    def test_ratios(self):
        r = c.performance_ratios(self.table)
        np.testing.assert_array_equal(r["A"].to_numpy(), [1.0, 1.0, np.inf, np.inf])
        np.testing.assert_array_equal(r["B"].to_numpy(), [2.0, 1.0, 1.0, np.inf])

    def test_profile_values(self):
        rho = c.profile(c.performance_ratios(self.table), [1.0, 1.5, 2.0, 100.0])
        # A: best on problems 1, 2 and never solves 3, 4. B: best on 2, 3; within 2x on 1.
        np.testing.assert_allclose(rho["A"], [0.5, 0.5, 0.5, 0.5])
        np.testing.assert_allclose(rho["B"], [0.5, 0.5, 0.75, 0.75])

    def test_profile_at_one_sums_to_at_least_the_solved_share(self):
        # Every problem some solver solves has a best solver (ties count for each).
        rho = c.profile(c.performance_ratios(self.table), [1.0])
        self.assertGreaterEqual(rho["A"][0] + rho["B"][0], 3 / 4)


class GrowthExponent(unittest.TestCase):
    def test_power_law(self):
        d = np.array([1352, 5202, 20402, 80802])
        self.assertAlmostEqual(c.growth_exponent(d, 3e-6 * d ** 1.5), 1.5)

    def test_too_few_points(self):
        self.assertTrue(math.isnan(c.growth_exponent([100], [1.0])))


class Aggregate(unittest.TestCase):
    """One set of two steps, two formulations: x solves both, y fails step 2."""

    def setUp(self):
        self.runs = pd.DataFrame({
            "problem": ["p"] * 3, "formulation": ["x", "y", "z"], "start": ["warm"] * 3,
            "status": ["converged", "failed", "skipped"], "message": ["", "", "cannot"],
            "settings": ["", "", ""], "time_limit_s": [5.0] * 3})
        self.steps = pd.DataFrame({
            "formulation": ["x", "x", "y", "y"], "start": ["warm"] * 4, "step": [1, 2, 1, 2],
            "time_s": [0.001, 0.001, 0.002, 0.1], "iterations": [2, 2, 4, 30],
            "accepted": [True, True, True, False], "mode": ["replay"] * 4})

    def test_table(self):
        table, skipped, time_charge, iter_charge = c.aggregate(self.runs, self.steps)
        self.assertEqual(list(skipped["formulation"]), ["z"])
        self.assertEqual((time_charge, iter_charge), (5.0, 30.0))
        x = table[table["formulation"] == "x"].iloc[0]
        y = table[table["formulation"] == "y"].iloc[0]
        self.assertEqual((x["success"], y["success"]), (1.0, 0.5))
        # x: 1 ms each step. y: 2 ms, and the failure charged at the 5 s limit = 5000 ms.
        self.assertAlmostEqual(x["sgm_time_ms"], 1.0)
        self.assertAlmostEqual(y["sgm_time_ms"], math.sqrt(12 * 5010) - 10)
        self.assertAlmostEqual(x["sgm_time_ms_ratio"], 1.0)
        self.assertAlmostEqual(y["sgm_time_ms_ratio"], math.sqrt(12 * 5010) - 10)
        # Iterations: y's failure charged at the largest count of the set (30).
        self.assertAlmostEqual(y["sgm_iterations"], math.sqrt(14 * 40) - 10)
        self.assertAlmostEqual(y["median_iterations"], 4)  # over accepted steps only

    def test_warm_gain(self):
        cold = self.steps.assign(start="cold", time_s=self.steps["time_s"] * 4)
        runs = pd.concat([self.runs, self.runs.assign(start="cold")])
        table, *_ = c.aggregate(runs, pd.concat([self.steps, cold]))
        gain = c.warm_gain(table).set_index("formulation")
        self.assertAlmostEqual(gain.loc["x", "median_time"], 4.0)
        self.assertAlmostEqual(gain.loc["x", "sgm_iterations"], 1.0)

    def test_time_range_over_repetitions_and_accepted_steps(self):
        # Without the repetition columns the range is over the accepted steps' times.
        table, *_ = c.aggregate(self.runs, self.steps)
        y = table[table["formulation"] == "y"].iloc[0]
        self.assertEqual((y["min_time_ms"], y["max_time_ms"]), (2.0, 2.0))  # step 2 failed
        # compare --repeat: the fastest and slowest repetition of the accepted steps.
        repeated = self.steps.assign(time_min_s=self.steps["time_s"] / 2,
                                     time_max_s=self.steps["time_s"] * 3, time_samples=5)
        table, *_ = c.aggregate(self.runs, repeated)
        x = table[table["formulation"] == "x"].iloc[0]
        self.assertAlmostEqual(x["min_time_ms"], 0.5)
        self.assertAlmostEqual(x["median_time_ms"], 1.0)
        self.assertAlmostEqual(x["max_time_ms"], 3.0)
        with tempfile.TemporaryDirectory() as d:
            self.assertIn("no run.json: the load is unknown", c.timing_line(d, repeated))
            with open(os.path.join(d, "run.json"), "w") as f:
                json.dump({"command": "compare"}, f)  # written before run.json had the load
            self.assertIn("the load was not recorded", c.timing_line(d, repeated))
            with open(os.path.join(d, "run.json"), "w") as f:
                json.dump({"load_average": {"start": {"1min": 1.5}, "end": {"1min": 2.25}}}, f)
            line = c.timing_line(d, repeated)
        self.assertIn("each solve timed 5 times", line)
        self.assertIn("load average (1 min) 1.50 at the start, 2.25 at the end", line)
        self.assertIn("each solve timed once", c.timing_line(d, self.steps))

    def test_histogram(self):
        h = c.histogram(self.steps, "y", "warm")
        self.assertEqual((h[4], h["failed"], sum(h[k] for k in range(13)) + h["more"]), (1, 1, 1))


class Targets(unittest.TestCase):
    """target_rows on a hand-made benchmark table: P1 times growing as d^1.2 exactly, a P3 ratio
    above the bound, a failed benchmark and missing ones."""

    def setUp(self):
        rows = []
        for n in (25, 50, 100, 200, 400):
            d = 2 * (n + 1) ** 2
            t = 1e-5 * d ** 1.2
            rows.append({"run_name": f"BM_BlockColdSolve/cholmod/{n}", "error_occurred": False,
                         "seconds": t, "cpu_seconds": t, "d": d, "newton_iterations": 13,
                         "solve_peak_mb": 2e-3 * d, "solve_bytes_per_dof": 2048.0})
        rows.append({"run_name": "BM_IterationOverFactorizationArchCurved/cholmod/100",
                     "error_occurred": False, "seconds": 3e-5, "cpu_seconds": 3e-5,
                     "ratio": 2.0, "kernel_ratio": 1.8, "per_newton_iteration_us": 60.0,
                     "lu_factorize_solve_us": 30.0})
        rows.append({"run_name": "BM_ArchCurvedWarmStep/cholmod/100", "error_occurred": True,
                     "seconds": 1e-4, "cpu_seconds": 1e-4})
        self.rows = {t: (m, ok) for t, m, ok in c.target_rows(pd.DataFrame(rows))}

    def test_bounds(self):
        p1 = self.rows["P1 n = 50 cold solve < 0.1 s"]
        self.assertIs(p1[1], 1e-5 * 5202 ** 1.2 < 0.1)
        ratio = self.rows["Newton iteration / KLU factorisation + solve of its Jacobian <= 1.5, "
                          "P3, step 100"]
        self.assertIs(ratio[1], False)
        self.assertIn("60 / 30 us = 2", ratio[0])

    def test_growth_is_fitted(self):
        growth = self.rows["P1 time growth, n = 50 to 400, <= d^1.3"]
        self.assertEqual((growth[0].split(" ")[0], growth[1]), ("d^1.20", True))

    def test_failed_and_missing_are_not_measured(self):
        self.assertEqual(self.rows["one warm P3 step (after step 100) < 0.5 ms"],
                         ("not measured", "not measured"))
        self.assertEqual(self.rows["whole P3 path (1604 steps, kinks located) < 1.5 s"],
                         ("not measured", "not measured"))
        self.assertIsNone(self.rows["peak memory of the P1 solve reported, linear in d"][1])


class SkippedLine(unittest.TestCase):
    def test_the_skipped_runs_of_a_set_are_one_line_each_reason_once(self):
        skipped = pd.DataFrame({
            "formulation": ["a", "a", "b", "b", "c"],
            "start": ["warm", "cold", "warm", "cold", "warm"],
            "message": ["a cannot express X", "a cannot express X", "b cannot express X",
                        "b cannot express X", "no Ipopt in this build"]})
        lines = c.skipped_line(skipped)
        self.assertEqual(lines, ["Skipped: a, b - cannot express X; c - no Ipopt in this build.",
                                 ""])

    def test_nothing_skipped_no_line(self):
        self.assertEqual(c.skipped_line(pd.DataFrame(columns=["formulation", "message"])), [])


if __name__ == "__main__":
    unittest.main()
