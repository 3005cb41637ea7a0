"""results/plotlib/solid3d.py: the Hertz measures on hand-made nodal reactions with known answers,
the observed rates, and the section with its figures on small real runs of hertz-3d and
plate-3d. The suite driver is $CONTACTBENCH_BINARY (ctest sets it), else build/bin/contactbench
of this tree."""
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np
import pandas as pd

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "results"))
from plotlib import solid3d  # noqa: E402

BINARY = os.environ.get("CONTACTBENCH_BINARY",
                        os.path.join(ROOT, "build", "bin", "contactbench"))
PNG = b"\x89PNG\r\n\x1a\n"


def bottom_face(coordinates, pressure):
    """solution.csv and contacts.csv of a bottom face on the grid `coordinates` x `coordinates`
    whose nodal reactions are pressure(x, y) times the node's tributary area."""
    width = solid3d._tributary_widths(coordinates)
    rows, pairs = [], []
    for node, (x, y) in enumerate((x, y) for y in coordinates for x in coordinates):
        rows.append({"node": node, "x": x, "y": y})
        pairs.append({"node": node, "r": -pressure(x, y) * width[x] * width[y]})
    return pd.DataFrame(rows), pd.DataFrame(pairs)


class HertzMeasures(unittest.TestCase):
    def test_closed_form_of_the_default_problem(self):
        a, p0 = solid3d.closed_form(30.0, 50.0, 1000.0, 0.3)
        self.assertAlmostEqual(a, 1.0079, places=4)  # docs/problems.md
        self.assertAlmostEqual(p0, 14.102, places=3)
        self.assertAlmostEqual(a ** 3, 3 * 30.0 * 50.0 / (4 * 1000.0 / (1 - 0.09)), places=12)

    def test_a_uniform_pressure_is_recovered_at_every_node(self):
        coordinates = np.array([0.0, 0.1, 0.4, 0.9, 1.6])
        solution, contacts = bottom_face(coordinates, lambda x, y: 3.0)
        pressures = solid3d.nodal_pressures(solution, contacts)
        np.testing.assert_allclose(pressures["pressure"], 3.0, rtol=1e-12)
        self.assertTrue(pressures["rho"].is_monotonic_increasing)

    def test_hertz_pressure_gives_its_radius_and_peak(self):
        a, p0 = 1.0, 14.0
        coordinates = np.linspace(0.0, 2.0, 801)

        def hertz(x, y):
            return p0 * math.sqrt(max(0.0, 1.0 - (x * x + y * y) / (a * a)))

        solution, contacts = bottom_face(coordinates, hertz)
        measured_a, measured_p0 = solid3d.measure(solution, contacts)
        self.assertAlmostEqual(measured_a, a, delta=2e-3)
        self.assertAlmostEqual(measured_p0, p0, delta=1e-6)


class Rates(unittest.TestCase):
    def test_observed_order_of_a_power_law(self):
        rates = solid3d.observed_rates([8, 16, 32], [0.1, 0.025, -0.00625])
        self.assertTrue(math.isnan(rates[0]))
        self.assertAlmostEqual(rates[1], 2.0)
        self.assertAlmostEqual(rates[2], 2.0)
        self.assertAlmostEqual(solid3d.fitted_rate([8, 16, 32], [0.1, 0.025, 0.00625]), 2.0)

    def test_a_zero_error_has_no_rate(self):
        self.assertTrue(math.isnan(solid3d.observed_rates([4, 8], [0.1, 0.0])[1]))

    def test_where_the_error_grows_is_read_from_the_errors(self):
        # |e|: 0.1, 0.05, 0.06 (grows 16 -> 24), -0.02, 0.03 (grows 32 -> 40); signs aside.
        n, e = [8, 16, 24, 32, 40], [0.1, -0.05, 0.06, -0.02, 0.03]
        self.assertEqual(solid3d.error_growth(n, e), [(16, 24), (32, 40)])
        self.assertEqual(solid3d.error_growth(n, [0.1, 0.05, -0.02, 0.01, 0.001]), [])


def contactbench(*args):
    subprocess.run([BINARY, "run", "--formulation", "implicit-fb", *args], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


@unittest.skipUnless(os.access(BINARY, os.X_OK), f"no suite driver at {BINARY}")
class Section(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="contactbench_solid3d_")
        for n in (3, 4):
            contactbench("--problem", "hertz-3d", "--set", f"n={n}", "--set", f"nz={n}",
                         "--out", os.path.join(cls.tmp, "solid3d", "hertz", f"n{n}"))
        contactbench("--problem", "plate-3d", "--steps", "20", "--save-every", "10",
                     "--out", os.path.join(cls.tmp, "solid3d", "plate-3d"))
        cls.lines = solid3d.section(cls.tmp)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def test_the_table_has_one_row_per_mesh_with_the_scripts_numbers(self):
        table = solid3d.hertz_table(self.tmp)
        self.assertEqual(list(table["n"]), [3, 4])
        self.assertEqual(list(table["d"]), [3 * (n + 1) ** 3 - 2 * (n + 1) ** 2 for n in (3, 4)])
        # docs/problems.md's table: n = 4 gives a = 1.0507 mm (+4.25 %), p0 = 12.016 N/mm^2.
        self.assertAlmostEqual(table["a"].iloc[1], 1.0507, places=4)
        self.assertAlmostEqual(table["p0"].iloc[1], 12.016, places=3)
        rows = [line for line in self.lines if line.startswith("| 4 |")]
        self.assertEqual(len(rows), 1)
        self.assertIn("+4.25 %", rows[0])

    def test_every_figure_is_written(self):
        figures = [line[line.index("](") + 2:-1] for line in self.lines if line.startswith("![")]
        self.assertEqual([os.path.basename(f) for f in figures],
                         ["hertz.png", "plate-path.png", "plate-deformed.png"])
        for f in figures:
            with open(os.path.join(self.tmp, f), "rb") as png:
                self.assertEqual(png.read(8), PNG, f)

    def test_the_plate_kinks_are_listed(self):
        kinks = pd.read_csv(os.path.join(self.tmp, "solid3d", "plate-3d", "kinks.csv"))
        self.assertGreater(len(kinks), 0)
        self.assertIn("%d kinks located, %d verified" % (len(kinks), len(kinks)),
                      "\n".join(self.lines))

    def test_thinned_records_give_the_same_section(self):
        thinned = tempfile.mkdtemp(prefix="contactbench_solid3d_thin_")
        self.addCleanup(shutil.rmtree, thinned)
        shutil.copytree(os.path.join(self.tmp, "solid3d"), os.path.join(thinned, "solid3d"))
        solid3d.thin_records(thinned)
        n4 = os.path.join(thinned, "solid3d", "hertz", "n4")
        self.assertEqual(sorted(os.listdir(n4)), sorted(solid3d.HERTZ_KEPT_FILES))
        self.assertFalse(os.path.isdir(os.path.join(thinned, "solid3d", "plate-3d", "vtk")))
        kept = pd.read_csv(os.path.join(n4, "solution.csv"))
        contacts = pd.read_csv(os.path.join(n4, "contacts.csv"))
        self.assertEqual(set(kept["node"]), set(contacts["node"]))
        self.assertEqual(solid3d.section(thinned), self.lines)

    def test_no_records_no_section(self):
        empty = tempfile.mkdtemp(prefix="contactbench_solid3d_empty_")
        try:
            self.assertIsNone(solid3d.section(empty))
        finally:
            shutil.rmtree(empty)


if __name__ == "__main__":
    unittest.main()
