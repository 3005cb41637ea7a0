#!/usr/bin/python3
"""How many early signals still end `contactbench run` by the default action (issue 30).

Starts a short run N times and sends SIGINT or SIGTERM (alternately) after a delay spread
evenly over [0, WINDOW] s; a run whose status is -SIGNAL died by the default action before its
handlers were installed, any other status was handled. Prints the count and the latest delay
at which a run still died. Usage:
    startup_signal_window.py CONTACTBENCH [N=96] [WINDOW=0.85]
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time


def trial(binary, out, delay, sig):
    shutil.rmtree(out, ignore_errors=True)
    process = subprocess.Popen(
        [binary, "run", "--problem", "two-bar", "--formulation", "implicit-fb", "--steps",
         "100000", "--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(delay)
    process.send_signal(sig)
    return process.wait() == -sig


def main():
    binary = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 96
    window = float(sys.argv[3]) if len(sys.argv) > 3 else 0.85
    out = os.path.join(tempfile.mkdtemp(prefix="startup_window_"), "out")
    died = []
    for k in range(count):
        delay = window * k / max(count - 1, 1)
        sig = signal.SIGINT if k % 2 == 0 else signal.SIGTERM
        if trial(binary, out, delay, sig):
            died.append(delay)
    shutil.rmtree(os.path.dirname(out), ignore_errors=True)
    latest = "%.3f s" % max(died) if died else "none"
    print("%d of %d trials died by the default action; the latest at %s"
          % (len(died), count, latest))


if __name__ == "__main__":
    main()
