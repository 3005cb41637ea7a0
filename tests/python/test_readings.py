"""The measures of results/plotlib/readings.py on small hand-made records whose answers are worked
out by hand. Run: /usr/bin/python3 -m unittest discover -s tests/python."""
import math
import os
import shutil
import sys
import tempfile
import unittest

import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results"))
from plotlib import readings as r  # noqa: E402


def steps_and_iterations():
    """Three steps. Step 1: one attempt, residuals 1e-5, 5e-10, 1e-14 (3 iterations at 1e-10, 2
    at 3e-9). Step 2: a rejected attempt 0 then attempt 1 with 1e-4, 2e-9, 1e-13. Step 3: a
    stagnated step the verdict accepted, never below 3e-9 (4 iterations either way)."""
    steps = pd.DataFrame({"step": [1, 2, 2, 3], "attempt": [0, 0, 1, 0],
                          "accepted": [1, 0, 1, 1], "iterations": [3, 7, 3, 4]})
    rows = [(1, 0, 1, 1e-5), (1, 0, 2, 5e-10), (1, 0, 3, 1e-14),
            (2, 0, 1, 1e-9),  # the rejected attempt: must not count
            (2, 1, 1, 1e-4), (2, 1, 2, 2e-9), (2, 1, 3, 1e-13),
            (3, 0, 1, 1e-3), (3, 0, 2, 1e-6), (3, 0, 3, 1e-8), (3, 0, 4, 5e-9)]
    iterations = pd.DataFrame(rows, columns=["step", "attempt", "iteration", "residual_inf"])
    return steps, iterations


class Rescore(unittest.TestCase):
    def test_hand_counted(self):
        steps, iterations = steps_and_iterations()
        self.assertEqual(r.rescored_iterations(steps, iterations, 3e-9).tolist(), [2, 2, 4])

    def test_the_suites_own_tolerance_gives_the_recorded_counts(self):
        steps, iterations = steps_and_iterations()
        self.assertEqual(r.rescored_iterations(steps, iterations, 1e-10).tolist(), [3, 3, 4])

    def test_a_looser_test_never_needs_more_iterations(self):
        steps, iterations = steps_and_iterations()
        counts = [r.rescored_iterations(steps, iterations, t).tolist()
                  for t in (1e-10, 1e-9, 3e-9, 1e-7, 1e-2)]
        for tight, loose in zip(counts, counts[1:]):
            self.assertTrue(all(b <= a for a, b in zip(tight, loose)))
        self.assertEqual(counts[-1], [1, 1, 1])


class TableDistance(unittest.TestCase):
    def test_same_shape_is_zero_whatever_the_totals(self):
        self.assertEqual(r.table_distance({"3": 2, "4": 1}, {"3": 200, "4": 100}), 0.0)

    def test_disjoint_is_one(self):
        self.assertEqual(r.table_distance({"2": 5}, {"3": 7, "4": 1}), 1.0)

    def test_hand_computed(self):
        # p = (0.5, 0.5, 0), q = (0.75, 0, 0.25): 1/2 (0.25 + 0.5 + 0.25) = 0.5.
        self.assertAlmostEqual(r.table_distance({"3": 1, "4": 1}, {"3": 3, "5": 1}), 0.5)

    def test_symmetric_and_empty(self):
        a, b = {"3": 10, "4": 3, "7": 1}, {"3": 1081, "4": 379, "5": 100}
        self.assertAlmostEqual(r.table_distance(a, b), r.table_distance(b, a))
        self.assertTrue(math.isnan(r.table_distance({}, b)))

    def test_binned_uses_the_report_bins(self):
        self.assertEqual(r.binned([2, 3, 3, 12, 15, 60]), {"2": 1, "3": 2, "12": 1, "13-20": 1,
                                                           "> 50": 1})


class CriticalPoints(unittest.TestCase):
    def critical(self, rows):
        return {"critical": pd.DataFrame(rows, columns=["step", "kind", "nonsmooth", "lambda"])}

    def test_c_a_hair_before_b_in_the_same_step(self):
        run = self.critical([(914, "limit", 0, 89.83727577), (914, "bifurcation", 0, 89.83727572)])
        b, c, first = r.critical_points(run)
        self.assertEqual(b["kind"], "limit")
        self.assertEqual(first["kind"], "bifurcation")
        self.assertTrue(r.order_of_b_and_c(b, c).startswith("C before B"))

    def test_b_then_c_and_an_earlier_instability(self):
        run = self.critical([(628, "stability_change", 1, 61.9), (886, "limit", 1, 86.97),
                             (990, "bifurcation", 0, 77.5)])
        b, c, first = r.critical_points(run)
        self.assertEqual(r.order_of_b_and_c(b, c), "B before C (steps 886, 990)")
        self.assertEqual(first["step"], 628)

    def test_missing(self):
        self.assertEqual(r.critical_points({"critical": None}), (None, None, None))
        self.assertEqual(r.order_of_b_and_c(None, None), "neither on the path")


class DescribePair(unittest.TestCase):
    def test_p2_pair_order(self):
        # P2: 28 inner upper nodes, then 31 lower nodes against each obstacle (nc = 90).
        self.assertEqual(r.describe_pair(0, 90, 30), "upper node 1 / upper obstacle")
        self.assertEqual(r.describe_pair(28 + 15, 90, 30), "lower node centre / upper obstacle")
        self.assertEqual(r.describe_pair(59 + 15, 90, 30), "lower node centre / lower obstacle")
        self.assertEqual(r.describe_pair(59 + 14, 90, 30),
                         "lower node 1 from the centre / lower obstacle")

    def test_aligned_pairs_are_named_symmetrically(self):
        # pratt, howe, x-braced in P2: 30 lower nodes, none at the centre (nc = 28 + 60).
        self.assertEqual(r.describe_pair(58 + 14, 88, 30), "lower node 0.5 from the centre / "
                         "lower obstacle")
        self.assertEqual(r.describe_pair(58 + 15, 88, 30), r.describe_pair(58 + 14, 88, 30))
        self.assertEqual(r.describe_pair(58 + 12, 88, 30), r.describe_pair(58 + 17, 88, 30))


class P2Measures(unittest.TestCase):
    def test_kinks_before_an_angular_b_and_its_contact_change(self):
        # B turns at a kink located between steps 885 and 886: two symmetric lower nodes, two
        # from the centre, change contact with the floor there (pairs 59 + 13 and 59 + 17).
        lam_b = 86.97447562191338
        run = {
            "steps": pd.DataFrame({"step": [1, 2, 3], "accepted": [1, 1, 1],
                                   "iterations": [3, 3, 2]}),
            "critical": pd.DataFrame([(628, "stability_change", 1, 61.9),
                                      (886, "limit", 1, lam_b)],
                                     columns=["step", "kind", "nonsmooth", "lambda"]),
            "kinks": pd.DataFrame([(8, 74, 0.42, 1, 1), (885, 72, lam_b, 1, 1),
                                   (885, 76, lam_b, 1, 1), (900, 70, 80.0, 1, 1),
                                   (950, 71, 70.0, 0, 1)],  # not verified: not counted
                                  columns=["step", "pair", "lambda", "verified", "between"]),
            "parameters": pd.DataFrame({"name": ["upper_nodes", "num_pairs"],
                                        "value": ["30", "90"]}),
        }
        m = r.p2_measures(run)
        self.assertEqual(m["kinks"], 4)
        self.assertEqual(m["kinks_before_B"], 3)
        self.assertEqual(m["B_pair"], "lower node 2 from the centre / lower obstacle (x2)")
        self.assertEqual(m["instability_before_B"]["step"], 628)
        self.assertEqual(m["order"], "B only (no C on the path)")


class WhatTheReadingsShow(unittest.TestCase):
    def measures(self, nonsmooth, order, kinks, instability=None):
        b = pd.Series({"step": 900, "lambda": 80.0, "nonsmooth": nonsmooth})
        return {"B": b, "order": order, "kinks": kinks, "instability_before_B": instability,
                "B_pair": None, "steps": 2000}

    def test_a_reading_with_the_reports_b_and_c_is_named(self):
        measured = {"default": self.measures(0, "C before B, 5.0e-08 apart in lambda", 38),
                    "a": self.measures(1, "B before C (steps 900, 950)", 40),
                    "b": self.measures(1, "B before C (steps 900, 950)", 30,
                                       pd.Series({"kind": "stability_change", "step": 600}))}
        text = "\n".join(r.what_the_readings_show(measured, {"x": (19, 38), "y": (19, 38)},
                                                  {}, {}))
        self.assertIn("B at a kink (a contact change, as in the report): a, b.", text)
        self.assertIn("with no instability before B: a.", text)
        self.assertIn("first a stability change at step 600", text)
        self.assertIn("Kinks over the traced path: 30 to 40 (most: a)", text)
        self.assertIn("19 / 38: the same at every arc length", text)

    def test_kinks_that_vary_are_said_to(self):
        text = "\n".join(r.what_the_readings_show({}, {"x": (19, 38), "y": (20, 39)}, {}, {}))
        self.assertIn("they depend on the arc length or the load unit", text)


if __name__ == "__main__":
    unittest.main()


P2_RECORDS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results",
                          "arch-flat", "newton")


@unittest.skipUnless(os.path.isdir(P2_RECORDS), "no committed P2 records")
class ThinnedRecords(unittest.TestCase):
    """thin_run keeps what the section reads: the committed P2 records (full, as a reading's run
    writes them) give the same measures before and after thinning, at every stopping test."""

    def test_the_measures_survive_thinning(self):
        tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, tmp)
        run_dir = os.path.join(tmp, "run")
        shutil.copytree(P2_RECORDS, run_dir)
        full = r.rep._run(tmp, "run")
        r.thin_run(run_dir)
        thin = r.rep._run(tmp, "run")
        self.assertIsNone(thin["iterations"])
        self.assertEqual(sorted(os.listdir(run_dir)), sorted(r.THIN_KEPT_FILES))
        self.assertTrue(thin["steps"]["accepted"].all())
        for tol in r.SWEEP + (r.REPORT_LIKE_TOL,):
            self.assertEqual(r.counts_at(full, tol).tolist(), r.counts_at(thin, tol).tolist())
            self.assertEqual(r.table_1_measures(full, tol), r.table_1_measures(thin, tol))
            self.assertEqual(r.table_2_measures(full, tol), r.table_2_measures(thin, tol))
        before, after = r.p2_measures(full), r.p2_measures(thin)
        self.assertEqual(before["order"], after["order"])
        self.assertEqual((before["steps"], before["kinks"], before["kinks_before_B"]),
                         (after["steps"], after["kinks"], after["kinks_before_B"]))
        self.assertEqual(before["B"]["lambda"], after["B"]["lambda"])
        # A looser test never takes more iterations: the rescored columns are not shuffled.
        counts = [r.counts_at(thin, t).tolist() for t in r.SWEEP]
        for tight, loose in zip(counts, counts[1:]):
            self.assertTrue(all(b <= a for a, b in zip(tight, loose)))
