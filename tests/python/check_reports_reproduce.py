#!/usr/bin/env python3
"""results/plot.py on the committed records alone writes the committed REPORT.md and
COMPARISON.md exactly: every table and sentence of both is made from records a fresh clone has.

Copies the files of results/ that git tracks (the whole of results/ outside a git checkout) into a
temporary directory, runs results/plot.py there and compares both reports line by line with the
committed ones; prints the differing lines and exits 1 when they differ.
Run: /usr/bin/python3 tests/python/check_reports_reproduce.py (ctest: python.reports_reproduce).
"""
import difflib
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
REPORTS = ("REPORT.md", "COMPARISON.md")


def committed_files():
    """The paths (relative to ROOT) of results/'s committed files, or None outside git."""
    try:
        done = subprocess.run(["git", "-C", ROOT, "ls-files", "-z", "results"],
                              capture_output=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    return [p for p in done.stdout.decode().split("\0") if p]


def copy_records(dest):
    files = committed_files()
    if files is None:
        shutil.copytree(os.path.join(ROOT, "results"), os.path.join(dest, "results"))
        return
    for rel in files:
        src = os.path.join(ROOT, rel)
        if os.path.isfile(src):
            os.makedirs(os.path.dirname(os.path.join(dest, rel)), exist_ok=True)
            shutil.copy2(src, os.path.join(dest, rel))


def main():
    with tempfile.TemporaryDirectory() as tmp:
        copy_records(tmp)
        results = os.path.join(tmp, "results")
        for name in REPORTS:  # written anew, not left over from the copy
            os.remove(os.path.join(results, name))
        # The working tree's generator on the committed records.
        subprocess.run([sys.executable, os.path.join(ROOT, "results", "plot.py"), results],
                       check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        failed = False
        for name in REPORTS:
            with open(os.path.join(ROOT, "results", name)) as f:
                committed = f.read().splitlines()
            with open(os.path.join(results, name)) as f:
                written = f.read().splitlines()
            diff = list(difflib.unified_diff(committed, written, "committed " + name,
                                             "from the committed records", lineterm="", n=0))
            if diff:
                failed = True
                print("\n".join(diff[:80]))
                print("%s: %d lines differ" % (name, sum(d[:1] in "+-" for d in diff[2:])))
            else:
                print("%s: reproduced exactly (%d lines)" % (name, len(committed)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
