"""results/plotlib/speed.py: COMPARISON.md's "Speed to the floor" table from a benchmark JSON
written here by hand, so that every cell can be checked against the numbers it came from."""
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results"))
from plotlib import speed  # noqa: E402


def run(name, seconds, stat="median", **counters):
    """One aggregate row of Google Benchmark's JSON (time in ms)."""
    row = {"name": f"{name}/iterations:1/manual_time_{stat}",
           "run_name": f"{name}/iterations:1/manual_time", "run_type": "aggregate",
           "aggregate_name": stat, "repetitions": 3, "real_time": seconds * 1e3,
           "cpu_time": seconds * 1e3, "time_unit": "ms"}
    row.update(counters)
    return row


def bench_json(rows):
    return {"context": {"load_avg": [1.0, 1.0, 1.0], "load_avg_end": [2.0, 1.0, 1.0],
                        "mhz_per_cpu": 2600}, "benchmarks": rows}


class SpeedSectionTest(unittest.TestCase):
    def section(self, rows):
        with tempfile.TemporaryDirectory() as d:
            os.makedirs(os.path.join(d, "bench"))
            with open(os.path.join(d, "bench", "speed_floor_benchmark.json"), "w") as f:
                json.dump(bench_json(rows), f)
            return speed.section(d)

    def test_cells_ratios_and_order(self):
        split = {"setup_s": 0.1, "factorization_s": 1.5, "iterations_s": 0.3, "recovery_s": 0.1,
                 "floor_s": 2.5, "time_over_floor": 0.8, "iterations": 13, "d": 321602}
        rows = []
        for stat, t in (("median", 2.0), ("min", 1.9), ("max", 2.4)):
            rows.append(run("block/implicit-fb/n:400", t, stat, **split))
        rows += [run("block/petsc-ssls/n:400", 12.0, iterations=13, d=321602),
                 run("block/petsc-rsls/n:400", 16.0, iterations=10, d=321602),
                 run("block/implicit-fb/n:100", 0.1, iterations=13, d=20402, **{
                     k: v for k, v in split.items() if k not in ("iterations", "d")})]
        text = "\n".join(self.section(rows))
        lines = [x for x in text.splitlines() if x.startswith("| P1 block")]
        self.assertEqual([x.split(" | ")[1] for x in lines], ["100", "400"])  # sorted by n
        cells = lines[1].split(" | ")
        self.assertIn("2 s (1.9-2.4), 13 it", cells[3])
        self.assertEqual(cells[4], "0.1 / 1.5 / 0.3 / 0.1")
        self.assertEqual(cells[5], "2.5 s (0.80x)")
        self.assertEqual(cells[-1].rstrip(" |"), "6.00")  # petsc-ssls 12 s over 2 s
        self.assertIn("3 repetitions", text)
        self.assertIn("2600 MHz", text)

    def test_a_skipped_peer_is_listed_with_its_reason(self):
        rows = [run("hertz-3d/implicit-fb/n:40", 20.0, iterations=18, d=203401),
                {"name": "hertz-3d/petsc-ssls/n:40/iterations:1/manual_time",
                 "run_name": "hertz-3d/petsc-ssls/n:40/iterations:1/manual_time",
                 "error_occurred": True, "error_message": "not run: time budget"}]
        text = "\n".join(self.section(rows))
        self.assertIn("(1)", text)
        self.assertIn("- (1) not run: time budget", text)

    def test_no_json_no_section(self):
        with tempfile.TemporaryDirectory() as d:
            self.assertEqual(speed.section(d), [])


if __name__ == "__main__":
    unittest.main()
