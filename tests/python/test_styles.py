"""plotlib/styles.py: a distinct style per formulation of the registry, the registry's list."""
import os
import subprocess
import sys
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "results"))
from plotlib import styles  # noqa: E402

BINARY = os.environ.get("CONTACTBENCH_BINARY",
                        os.path.join(ROOT, "build", "bin", "contactbench"))


class Styles(unittest.TestCase):
    def test_every_formulation_has_a_style_of_its_own(self):
        seen = {}
        for f in styles.FORMULATIONS:
            s = styles.style(f)
            key = (s["color"], s["marker"], s["markerfacecolor"])
            self.assertNotIn(key, seen, f"{f} and {seen.get(key)}")
            seen[key] = f

    def test_a_distributed_variant_is_its_base_hollow(self):
        base, dist = styles.style("petsc-rsls"), styles.style("dist-petsc-rsls")
        self.assertEqual((base["color"], base["marker"]), (dist["color"], dist["marker"]))
        self.assertEqual(dist["markerfacecolor"], "none")

    @unittest.skipUnless(os.access(BINARY, os.X_OK), f"no suite driver at {BINARY}")
    def test_the_list_is_the_registrys(self):
        listing = subprocess.run([BINARY, "list"], capture_output=True, text=True,
                                 check=True).stdout.splitlines()
        start = listing.index("formulations:") + 1
        names = []
        for line in listing[start:]:
            if not line.startswith("  "):
                break
            names.append(line.split()[0])
        self.assertEqual(names, styles.FORMULATIONS)


if __name__ == "__main__":
    unittest.main()
