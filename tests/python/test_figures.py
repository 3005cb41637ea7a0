"""The report's figures on small hand-made records: the iteration histograms share one binning
and turn logarithmic when small bins would vanish, the P2 path's inset holds both B and C, and
the deformed shapes draw the run's obstacles. Run: /usr/bin/python3 -m unittest discover -s
tests/python."""
import os
import shutil
import sys
import tempfile
import unittest
from unittest import mock

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results"))
from plotlib import comparison, histograms, obstacles, reproduction  # noqa: E402
from plotlib import run_plots  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402  (plotlib chose the backend)


def comparison_records(iterations):
    """runs and steps of a warm-only comparison: {formulation: iteration count per step}."""
    runs = pd.DataFrame({"formulation": list(iterations), "start": "warm", "status": "ok"})
    steps = pd.concat([pd.DataFrame({"formulation": f, "start": "warm", "accepted": 1,
                                     "iterations": its, "step": range(len(its))})
                       for f, its in iterations.items()])
    return runs, steps


def panels(fig):
    return [ax for ax in fig.axes if ax.axison]


class HistogramFigure(unittest.TestCase):
    def figure(self, iterations):
        runs, steps = comparison_records(iterations)
        fig = comparison.histogram_figure("t", runs, steps, lambda f: "iterations")
        self.addCleanup(plt.close, fig)
        return fig

    def test_every_panel_has_the_bins_of_the_largest_count(self):
        # Alone, "short" would get the bins 0..4 and "long" doubling ranges up to 33-64.
        fig = self.figure({"short": [2, 2, 3], "long": [2, 40]})
        labels = [[t.get_text() for t in ax.get_xticklabels()] for ax in panels(fig)]
        self.assertEqual(len(labels), 2)
        self.assertEqual(labels[0], labels[1])
        self.assertEqual(labels[0][-1], "33-64")
        self.assertIn("3-4", labels[0])

    def test_many_bins_are_turned_so_that_they_do_not_overlap(self):
        fig = self.figure({"long": [2, 200]})
        ticks = panels(fig)[0].get_xticklabels()
        self.assertGreater(len(ticks), histograms.UPRIGHT_BINS)
        self.assertTrue(all(t.get_rotation() == 45 for t in ticks))

    def test_a_tail_of_single_steps_turns_the_count_axis_logarithmic(self):
        fig = self.figure({"a": [2] * 500 + [9], "b": [3] * 5})
        for ax in panels(fig):
            self.assertEqual(ax.get_yscale(), "log")
            self.assertIn("log scale", ax.get_ylabel())
            self.assertLess(ax.get_ylim()[0], 1)  # a bin of one step shows

    def test_comparable_counts_keep_a_linear_axis(self):
        fig = self.figure({"a": [2] * 5 + [3] * 3, "b": [3] * 4})
        for ax in panels(fig):
            self.assertEqual(ax.get_yscale(), "linear")
            self.assertNotIn("log", ax.get_ylabel())

    def test_wants_log_looks_at_the_nonzero_counts(self):
        self.assertFalse(histograms.wants_log([0, 0, 30, 1]))
        self.assertTrue(histograms.wants_log([[0, 31], [1, 0]]))
        self.assertFalse(histograms.wants_log([0, 7]))


def path_run():
    """A path through two points B and C 5e-8 apart in lambda, on a scale of 100."""
    disp = np.linspace(0.0, 3.0, 31)
    steps = pd.DataFrame({"step": range(31), "accepted": 1, "branch": 0,
                          "control_disp": disp, "lambda": 30.0 * disp})
    return {"steps": steps, "kinks": None}


class PathInset(unittest.TestCase):
    def test_the_window_holds_both_points_with_a_margin(self):
        (x0, x1), (y0, y1) = reproduction.inset_window([(3.0, 90.0), (3.0, 90.00000005)],
                                                       3.0, 100.0)
        for y in (90.0, 90.00000005):
            self.assertLess(y0, y)
            self.assertGreater(y1, y)
        # Half sizes 1.5 times the separation: a window 3 separations tall.
        self.assertAlmostEqual((y1 - y0) / 5e-8, 3.0, places=5)
        self.assertAlmostEqual((x1 - x0) / 3.0, (y1 - y0) / 100.0)  # the main proportions

    def test_coinciding_points_still_give_a_window(self):
        (x0, x1), (y0, y1) = reproduction.inset_window([(1.0, 2.0), (1.0, 2.0)], 1.0, 1.0)
        self.assertGreater(x1, x0)
        self.assertGreater(y1, y0)

    def test_the_inset_shows_b_and_c_with_their_own_markers(self):
        run = path_run()
        b = pd.Series({"control_disp": 2.0, "lambda": 60.0})
        c = pd.Series({"control_disp": 2.0, "lambda": 60.00000005})
        labels = {"B": (b, "s"), "C": (c, "D")}
        fig, ax = plt.subplots()
        self.addCleanup(plt.close, fig)
        inset = reproduction._zoom_inset(ax, run, labels, ("B", "C"))
        self.assertIn(inset, ax.child_axes)
        (x0, x1), (y0, y1) = inset.get_xlim(), inset.get_ylim()
        markers = {}
        for line in inset.get_lines():
            if line.get_gid() in ("B", "C"):
                markers[line.get_gid()] = line.get_marker()
                x, y = line.get_xdata()[0], line.get_ydata()[0]
                self.assertTrue(x0 < x < x1 and y0 < y < y1, line.get_gid())
        self.assertEqual(set(markers), {"B", "C"})
        self.assertNotEqual(markers["B"], markers["C"])

    def test_no_inset_without_both_points(self):
        fig, ax = plt.subplots()
        self.addCleanup(plt.close, fig)
        b = pd.Series({"control_disp": 2.0, "lambda": 60.0})
        self.assertIsNone(reproduction._zoom_inset(ax, path_run(), {"B": (b, "s")}, ("B", "C")))
        self.assertEqual(ax.child_axes, [])


VTP = """<?xml version="1.0"?>
<VTKFile type="PolyData" version="0.1"><PolyData>
<Piece NumberOfPoints="2" NumberOfLines="1">
<Points><DataArray type="Float64" NumberOfComponents="3">-1 -0.5 0 3 -0.5 0</DataArray></Points>
<Lines><DataArray type="Int64" Name="connectivity">0 1</DataArray>
<DataArray type="Int64" Name="offsets">2</DataArray></Lines>
</Piece></PolyData></VTKFile>
"""


class DeformedShape(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="contactbench_figures_")
        self.addCleanup(shutil.rmtree, self.dir)
        os.makedirs(os.path.join(self.dir, "vtk"))
        with open(os.path.join(self.dir, "vtk", "bar_obstacle_0.vtp"), "w") as f:
            f.write(VTP)
        snapshots = pd.DataFrame({"step": 5, "label": "final", "lambda": 1.0, "node": [0, 1],
                                  "x": [0.0, 2.0], "y": [0.0, 0.0], "ux": [0.0, 0.1],
                                  "uy": [0.0, -0.4]})
        cells = pd.DataFrame({"cell": [0, 0], "corner": [0, 1], "node": [0, 1]})
        self.run = {"snapshots": snapshots, "cells": cells, "snapshot_contacts": None,
                    "dir": self.dir}

    def test_the_obstacles_are_drawn_over_the_mesh(self):
        figures = []
        with mock.patch.object(reproduction, "_save", lambda fig, d, name: figures.append(fig)):
            reproduction._deformed_figure(self.dir, self.run, "final", "t", "d.png")
        self.addCleanup(plt.close, figures[0])
        ax = figures[0].axes[0]
        drawn = [line for line in ax.get_lines() if line.get_gid() == obstacles.GID]
        self.assertEqual(len(drawn), 1)
        np.testing.assert_allclose(drawn[0].get_ydata(), [-0.5, -0.5])
        # The window is the mesh's, with the obstacle's line in it.
        y0, y1 = ax.get_ylim()
        self.assertTrue(y0 < -0.5 < y1)
        self.assertIn("obstacles", ax.get_legend_handles_labels()[1])

    def test_plot_run_draws_the_same_obstacles(self):
        records = dict(self.run, steps=pd.DataFrame({"problem": ["bar"]}), run={})
        figures = []
        with mock.patch.object(run_plots, "_save", lambda fig, path: figures.append(fig)):
            run_plots.plot_deformed(records, "deformed.png")
        self.addCleanup(plt.close, figures[0])
        drawn = [line for line in figures[0].axes[0].get_lines()
                 if line.get_gid() == obstacles.GID]
        self.assertEqual(len(drawn), 1)
        np.testing.assert_allclose(drawn[0].get_xdata(), [-1.0, 3.0])


if __name__ == "__main__":
    unittest.main()
