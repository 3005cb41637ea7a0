"""results/plot_run.py on the records of real runs of a problem file (a run and a comparison):
every figure is written as a PNG, and the geometry drawn is the records' own. The suite
driver is $CONTACTBENCH_BINARY (ctest sets it), else build/bin/contactbench of this tree."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from unittest import mock

import numpy as np
import pandas as pd

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "results"))
from plotlib import obstacles, run_plots  # noqa: E402

BINARY = os.environ.get("CONTACTBENCH_BINARY",
                        os.path.join(ROOT, "build", "bin", "contactbench"))
PNG = b"\x89PNG\r\n\x1a\n"


def contactbench(*args):
    subprocess.run([BINARY, *args], check=True, stderr=subprocess.DEVNULL)


@unittest.skipUnless(os.access(BINARY, os.X_OK), f"no suite driver at {BINARY}")
class PlotRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="contactbench_plot_run_")
        example = os.path.join(ROOT, "examples", "truss-2d-bar-wall.json")
        cls.run_dir = os.path.join(cls.tmp, "run")
        contactbench("run", "--problem-file", example, "--formulation", "implicit-fb",
                     "--save-every", "10", "--out", cls.run_dir)
        cls.compare_dir = os.path.join(cls.tmp, "compare")
        contactbench("compare", "--problem-file", example, "--formulations",
                     "implicit-fb,nonsmooth-fb", "--starts", "warm,cold", "--out", cls.compare_dir)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def assert_pngs(self, written, names):
        self.assertEqual(sorted(os.path.basename(p) for p in written), sorted(names))
        for path in written:
            with open(path, "rb") as f:
                self.assertEqual(f.read(8), PNG, path)
            self.assertGreater(os.path.getsize(path), 10000, path)

    def test_the_script_draws_every_figure_of_a_run(self):
        figures = os.path.join(self.tmp, "run-figures")
        status = subprocess.run([sys.executable, os.path.join(ROOT, "results", "plot_run.py"),
                                 self.run_dir, "--figures", figures, "--step", "14"]).returncode
        self.assertEqual(status, 0)
        self.assert_pngs([os.path.join(figures, f) for f in os.listdir(figures)],
                         ["path.png", "deformed.png", "cost.png", "residual.png"])

    def test_a_comparison_adds_the_profiles_and_histograms(self):
        written = run_plots.write(self.compare_dir, os.path.join(self.tmp, "compare-figures"))
        self.assert_pngs(written, ["path.png", "cost.png", "residual.png", "profiles.png",
                                   "histograms.png"])

    def test_the_default_residual_history_is_the_hardest_step(self):
        records = run_plots.read_run(self.run_dir)
        steps = records["steps"]
        hardest = run_plots.hardest_step(records)
        self.assertEqual(steps[steps["step"] == hardest]["iterations"].max(),
                         steps["iterations"].max())

    def test_a_step_without_iterations_is_refused(self):
        with self.assertRaises(ValueError):
            run_plots.plot_residual(run_plots.read_run(self.run_dir),
                                    os.path.join(self.tmp, "none.png"), 10 ** 6)

    def test_the_deformed_mesh_is_reference_plus_displacement(self):
        records = run_plots.read_run(self.run_dir)
        snap = records["snapshots"]
        final = snap[snap["label"] == "final"]
        segments = run_plots._state_segments(final, records["cells"], ["x", "y"])
        self.assertEqual(len(segments), records["cells"]["cell"].nunique())  # two-node members
        moved = final.set_index("node")
        first = records["cells"].sort_values(["cell", "corner"]).iloc[0]["node"]
        np.testing.assert_allclose(segments[0][0], [moved.loc[first, "x"] + moved.loc[first, "ux"],
                                                    moved.loc[first, "y"] + moved.loc[first, "uy"]])

    def test_the_obstacles_are_read_from_the_runs_vtk_files(self):
        # The wall: the half-plane x > 1.01, drawn as one line on x = 1.01.
        read = obstacles.read(self.run_dir)
        self.assertEqual(len(read), 1)
        name, points, lines = read[0]
        self.assertEqual(lines, [[0, 1]])
        np.testing.assert_allclose(points[:, 0], [1.01, 1.01])

    def test_not_a_run_directory_is_refused(self):
        with self.assertRaises(ValueError):
            run_plots.read_run(self.tmp)


@unittest.skipUnless(os.access(BINARY, os.X_OK), f"no suite driver at {BINARY}")
class PlotSolid(unittest.TestCase):
    """The deformed shapes of a small hertz-3d run (4 x 4 x 3 hexahedra)."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="contactbench_plot_solid_")
        cls.run_dir = os.path.join(cls.tmp, "run")
        contactbench("run", "--problem", "hertz-3d", "--set", "n=4", "--set", "nz=3",
                     "--formulation", "implicit-fb", "--out", cls.run_dir)
        cls.records = run_plots.read_run(cls.run_dir)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def test_the_segments_are_each_hexahedrons_twelve_edges(self):
        snap, cells = self.records["snapshots"], self.records["cells"]
        final = snap[snap["label"] == "final"]
        segments = run_plots._state_segments(final, cells, ["x", "y", "z"])
        self.assertEqual(len(segments), 12 * cells["cell"].nunique())
        # Each segment of the first hexahedron joins two corners that differ in one
        # coordinate of the (axis-aligned) reference mesh: an edge, never a face diagonal.
        reference = final.assign(ux=0.0, uy=0.0, uz=0.0)
        first = run_plots._state_segments(reference, cells, ["x", "y", "z"])[:12]
        for a, b in first:
            self.assertEqual(int(np.sum(~np.isclose(a, b))), 1, (a, b))

    def test_the_outer_edges_are_hexahedron_edges_on_the_surface(self):
        cells = self.records["cells"]
        ids = cells.sort_values(["cell", "corner"])["node"].to_numpy().reshape(-1, 8)
        hex_edges = {tuple(sorted((h[a], h[b]))) for h in ids for a, b in run_plots.HEX_EDGES}
        outer = {tuple(e) for e in run_plots.outer_edges(cells)}
        self.assertTrue(outer <= hex_edges)
        self.assertLess(len(outer), len(hex_edges))  # the inner edges are left out

    def test_each_panel_is_two_collections_and_the_panels_differ(self):
        figures = []
        with mock.patch.object(run_plots, "_save", lambda fig, path: figures.append(fig)):
            run_plots.plot_deformed(self.records, "deformed.png")
        fig = figures[0]
        self.addCleanup(plt.close, fig)
        titles = [ax.get_title() for ax in fig.axes]
        self.assertEqual(len(set(titles)), len(titles), titles)
        self.assertEqual(titles[0], "reference configuration")
        for ax in fig.axes:
            # The mesh and the obstacles, one collection each; at most one line (contacts).
            self.assertEqual(len(ax.collections), 2, ax.get_title())
            self.assertLessEqual(len(ax.lines), 1)
            self.assertEqual(ax.collections[1].get_gid(), obstacles.GID)


class StateSegments(unittest.TestCase):
    def test_a_quad_is_closed_and_moved(self):
        nodes = pd.DataFrame({"node": [0, 1, 2, 3], "x": [0.0, 1.0, 1.0, 0.0],
                              "y": [0.0, 0.0, 1.0, 1.0], "ux": [0.0, 0.5, 0.5, 0.0],
                              "uy": [0.0, 0.0, 0.0, 0.0]})
        cells = pd.DataFrame({"cell": [0, 0, 0, 0], "corner": [0, 1, 2, 3], "node": [0, 1, 2, 3]})
        segments = run_plots._state_segments(nodes, cells, ["x", "y"])
        self.assertEqual(len(segments), 4)
        np.testing.assert_allclose(segments[1], [[1.5, 0.0], [1.5, 1.0]])
        np.testing.assert_allclose(segments[3][1], [0.0, 0.0])  # back to the first corner


if __name__ == "__main__":
    unittest.main()
