"""`contactbench plot` on every record directory the suite driver can leave behind (issue 30):
a run that stopped before its first step, records edited by hand, a --figures that names a
file, a figure planted as a symbolic link. Each one is refused with a sentence naming the
file or directory (exit 2), never a traceback. The suite driver is $CONTACTBENCH_BINARY
(ctest sets it), else build/bin/contactbench of this tree."""
import os
import resource
import shutil
import subprocess
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
BINARY = os.environ.get("CONTACTBENCH_BINARY",
                        os.path.join(ROOT, "build", "bin", "contactbench"))


def contactbench(*args, file_limit=None):
    """(exit status, standard error) of the driver, with a file size limit in bytes."""
    def limit():
        if file_limit is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (file_limit, resource.RLIM_INFINITY))
    done = subprocess.run([BINARY, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True, preexec_fn=limit)
    return done.returncode, done.stderr


@unittest.skipUnless(os.access(BINARY, os.X_OK), f"no suite driver at {BINARY}")
class PlotRefusals(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="contactbench_plot_refusals_")
        cls.run_dir = os.path.join(cls.tmp, "run")
        status, err = contactbench("run", "--problem", "two-bar", "--formulation",
                                   "implicit-fb", "--out", cls.run_dir)
        assert status == 0, err

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def copy_of_run(self, name):
        copy = os.path.join(self.tmp, name)
        shutil.copytree(self.run_dir, copy)
        return copy

    def assert_refused(self, args, *words):
        status, err = contactbench("plot", *args)
        self.assertEqual(status, 2, err)
        self.assertNotIn("Traceback", err)
        for word in words:
            self.assertIn(word, err)

    def test_a_run_that_stopped_before_its_first_step_is_refused_with_its_reason(self):
        # A real exit-3 run: a file size limit of 1 KiB fails a record write before any step
        # (and run.json, too large for it).
        out = os.path.join(self.tmp, "full")
        status, err = contactbench("run", "--problem", "arch-curved", "--formulation",
                                   "implicit-fb", "--out", out, file_limit=1024)
        self.assertEqual(status, 3, err)
        with open(os.path.join(out, "steps.csv")) as f:
            self.assertEqual(len(f.readlines()), 1)  # the header alone
        self.assert_refused([out], "stopped before its first step")

    def test_figures_naming_a_file_is_refused(self):
        existing = os.path.join(self.tmp, "a-file")
        with open(existing, "w") as f:
            f.write("kept\n")
        self.assert_refused([self.run_dir, "--figures", existing], "--figures", existing)
        with open(existing) as f:
            self.assertEqual(f.read(), "kept\n")

    def test_a_record_file_that_is_not_csv_is_named(self):
        broken = self.copy_of_run("broken")
        with open(os.path.join(broken, "steps.csv"), "a") as f:
            f.write('garbage,"\n')
        self.assert_refused([broken], os.path.join(broken, "steps.csv"))
        with open(os.path.join(broken, "run.json"), "w") as f:
            f.write("{")
        with open(os.path.join(broken, "steps.csv"), "w") as f:
            f.write("")
        self.assert_refused([broken], "no steps.csv")

    def test_overwrite_removes_the_figures_of_the_run_it_replaces(self):
        out = self.copy_of_run("replaced")
        status, err = contactbench("plot", out)
        self.assertEqual(status, 0, err)
        self.assertTrue(os.path.isdir(os.path.join(out, "figures")))
        status, err = contactbench("run", "--problem", "two-bar", "--formulation",
                                   "nonsmooth-fb", "--overwrite", "--out", out)
        self.assertEqual(status, 0, err)
        self.assertFalse(os.path.exists(os.path.join(out, "figures")))

    def test_a_figure_planted_as_a_link_is_not_written_through(self):
        figures = os.path.join(self.tmp, "planted-figures")
        os.makedirs(figures)
        victim = os.path.join(self.tmp, "victim")
        with open(victim, "w") as f:
            f.write("precious\n")
        os.symlink(victim, os.path.join(figures, "path.png"))
        self.assert_refused([self.run_dir, "--figures", figures], "symbolic link")
        with open(victim) as f:
            self.assertEqual(f.read(), "precious\n")


if __name__ == "__main__":
    unittest.main()
