"""`contactbench compare --problem-dir tests/data/fclib` makes COMPARISON.md's problem-set section.

  /usr/bin/python3 tests/python/check_problem_set_section.py CONTACTBENCH_BINARY

Runs the problem set of the committed FCLIB files (friction dropped, four formulations, one of
which refuses a non-symmetric problem) into a scratch results directory, runs results/plot.py
on it and checks that the section states what problems.csv says and nothing else: one table
row per formulation and start kind with its verified and refused counts, medians and largest
FCLIB error recomputed here from the records; the problems listed are those of the records;
the profile figure is a PNG. A second set (a listed FCLIB file, a JSON LCP and a file that is
no problem file) checks that an unreadable file is listed with its reason and left out of the
tables. Exit status 77 (skipped) when the build reads no FCLIB files.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import pandas as pd

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "results"))
from plotlib import comparison, problem_sets  # noqa: E402

BINARY = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "bin", "contactbench")


def built_formulations():
    """The formulations the binary lists without "(not built)" (`contactbench list`)."""
    listing = subprocess.run([BINARY, "list"], capture_output=True, text=True).stdout
    return {m.group(1) for m in re.finditer(r"^  (\S+) (?!\(not built\))", listing, re.M)}


# Siconos' Lemke where the build has Siconos (the sanitizer build has not), else the semismooth
# FB method: four formulations either way, one of them refusing a non-symmetric problem.
FORMULATIONS = "active-set,implicit-fb,ipopt-energy," + (
    "siconos-lemke" if "siconos-lemke" in built_formulations() else "nonsmooth-fb")
PNG = b"\x89PNG\r\n\x1a\n"


def set_text(report, name):
    """The section of set `name`, up to the next heading."""
    section = report[report.index(f"### Problem set `{name}`"):]
    return re.split(r"^##", section[3:], maxsplit=1, flags=re.M)[0]


def table_rows(markdown, heading):
    """The rows (lists of cells) of the first table after `heading`."""
    lines = markdown[markdown.index(heading):].splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("| formulation |"))
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip("|").split("|")])
    return rows


class ProblemSetSection(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="contactbench_problem_set_")
        cls.set_dir = os.path.join(cls.tmp, "compare", "fclib")
        subprocess.run([BINARY, "compare", "--problem-dir",
                        os.path.join(ROOT, "tests", "data", "fclib"), "--set",
                        "friction=ignore", "--formulations", FORMULATIONS, "--repeat", "2",
                        "--time-limit", "5", "--out", cls.set_dir],
                       check=True, stderr=subprocess.DEVNULL)
        # A second set: a listed FCLIB file, a JSON LCP and a file that is no problem file.
        cls.broken = os.path.join(cls.tmp, "broken.json")
        with open(cls.broken, "w") as f:
            f.write("{ not json")
        cls.mixed_dir = os.path.join(cls.tmp, "compare", "mixed")
        listed = ",".join([os.path.join(ROOT, "tests", "data", "fclib", "CubeH8.hdf5"),
                           os.path.join(ROOT, "examples", "lcp-dense-2x2.json"), cls.broken])
        subprocess.run([BINARY, "compare", "--problem-dir", listed, "--set", "friction=ignore",
                        "--formulations", "active-set", "--out", cls.mixed_dir],
                       check=True, stderr=subprocess.DEVNULL)
        subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "results", "plot.py"), cls.tmp],
                       check=True, stderr=subprocess.DEVNULL)
        with open(os.path.join(cls.tmp, "COMPARISON.md")) as f:
            cls.report = f.read()
        cls.rows = pd.read_csv(os.path.join(cls.set_dir, "problems.csv"))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def test_every_problem_formulation_and_start_has_a_row(self):
        files = sorted(f for f in os.listdir(os.path.join(ROOT, "tests", "data", "fclib"))
                       if f.endswith(".hdf5"))
        self.assertEqual(sorted(set(self.rows["source"].map(os.path.basename))), files)
        per_start = self.rows.groupby(["problem", "start"])["formulation"].apply(sorted)
        for formulations in per_start:
            self.assertEqual(formulations, sorted(FORMULATIONS.split(",")))
        self.assertTrue((self.rows[self.rows["status"] != "skipped"]["time_samples"] == 2).all())

    def test_table_states_the_records(self):
        rows = table_rows(self.report, "### Problem set `fclib`")
        self.assertTrue(rows)
        records = self.rows.assign(kind=self.rows["start"].map(problem_sets.start_kind))
        self.assertEqual(len(rows), records.groupby(["formulation", "kind"]).ngroups)
        for cells in rows:
            formulation, kind, verified, refused, iterations, _, error_median, error_max = cells
            g = records[(records["formulation"] == formulation) & (records["kind"] == kind)]
            taken = g[g["status"] != "skipped"]
            solved = taken[taken["status"] == "verified"]
            self.assertEqual(verified, f"{len(solved)}/{len(taken)}", cells)
            self.assertEqual(int(refused), (g["status"] == "skipped").sum(), cells)
            self.assertEqual(iterations, comparison.fmt(solved["iterations"].median()), cells)
            self.assertEqual(error_median, comparison.fmt(solved["fclib_error"].median()), cells)
            self.assertEqual(error_max, comparison.fmt(solved["fclib_error"].max()), cells)

    def test_problems_listed_are_those_of_the_records(self):
        section = set_text(self.report, "fclib")
        listed = re.findall(r"^\| (\S+) \| (\d+) \| (\d+) \|", section, re.M)
        expected = self.rows.drop_duplicates("problem")
        self.assertEqual([(p, int(d), int(nc)) for p, d, nc in listed],
                         list(zip(expected["problem"], expected["d"], expected["nc"])))

    def test_profile_figure_is_written_and_linked(self):
        name = "problem_set_fclib_profiles.png"
        self.assertIn(f"(figures/comparison/{name})", self.report)
        with open(os.path.join(self.tmp, "figures", "comparison", name), "rb") as f:
            self.assertEqual(f.read(8), PNG)

    def test_unreadable_files_are_listed_and_left_out(self):
        mixed = pd.read_csv(os.path.join(self.mixed_dir, "problems.csv"))
        bad = mixed[mixed["status"] == "unreadable"]
        self.assertEqual(list(bad["source"]), [self.broken])
        section = set_text(self.report, "mixed")
        line = next(x for x in section.splitlines() if x.startswith("- `broken.json`: "))
        self.assertEqual(line, f"- `broken.json`: {bad['message'].iloc[0]}")
        listed = re.findall(r"^\| (\S+) \| (\d+) \| (\d+) \|", section, re.M)
        read = mixed[mixed["status"] != "unreadable"]["problem"]
        self.assertEqual([p for p, _, _ in listed], list(dict.fromkeys(read)))
        rows = table_rows(self.report, "### Problem set `mixed`")
        self.assertEqual([(r[0], r[1], r[2]) for r in rows],
                         [("active-set", "cold",
                           f"{(mixed['status'] == 'verified').sum()}/{len(read)}")])

    def test_friction_drop_is_said(self):
        self.assertIn("Friction was dropped (mu set to 0) in 5 of 5 problems", self.report)


def main():
    if not os.access(BINARY, os.X_OK):
        print(f"no suite driver at {BINARY}", file=sys.stderr)
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        probe = subprocess.run([BINARY, "export", "--problem", "block", "--set", "n=2",
                                "--format", "fclib", "--out", os.path.join(tmp, "b.hdf5")],
                               capture_output=True, text=True)
    if "has no HDF5" in probe.stderr:
        print("built without HDF5: no FCLIB files", file=sys.stderr)
        return 77
    result = unittest.main(argv=sys.argv[:1], exit=False).result
    return 0 if result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
