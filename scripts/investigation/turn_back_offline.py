#!/usr/bin/env python3
"""The turn-back guard of the path driver judged offline on a run's accepted states.

For every accepted step k whose increment points against the one before (H inner product of
(33), weight w of the load), prints the distance of x_k from
  (a) the last segment x_{k-2} x_{k-1}: the guard of src/path/turn_back.cc, and
  (b) the traced path back over 2 theta (and on behind the start, along the first increment):
      a guard against the traced path,
each in units of the step's theta; a guard rejects at <= 0.05 theta. Needs the state of every
accepted step: `contactbench run ... --save-every 1` (snapshots.csv; steps.csv for theta).
issue 25 and docs/findings.md ("What moves with rounding").

Usage: turn_back_offline.py RUN_DIR [RUN_DIR ...] [--weight W]
"""
import argparse
import csv
import math
import os


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def states(run):
    """[(step, [u..., lambda])] of the accepted states, the initial state (0) first."""
    saved = {}
    for r in rows(os.path.join(run, "snapshots.csv")):
        if r["label"] != "step":
            continue
        values = [float(r[c]) for c in ("ux", "uy", "uz") if c in r and r[c] != ""]
        saved.setdefault(int(r["step"]), (float(r["lambda"]), {}))[1][int(r["node"])] = values
    out = []
    for step in sorted(saved):
        lam, nodes = saved[step]
        out.append((step, [v for k in sorted(nodes) for v in nodes[k]] + [lam]))
    if out:
        out.insert(0, (0, [0.0] * len(out[0][1])))
    return out


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def dot(a, b, w):
    return sum(x * y for x, y in zip(a[:-1], b[:-1])) + w * w * a[-1] * b[-1]


def distance(p, a, b, w, ray=False):
    """H-distance from p to the segment a b (to the ray from a through b when ray)."""
    ab, ap = sub(b, a), sub(p, a)
    bb = dot(ab, ab, w)
    t = dot(ap, ab, w) / bb if bb > 0 else 0.0
    t = max(t, 0.0) if ray else min(max(t, 0.0), 1.0)
    e = [x - t * y for x, y in zip(ap, ab)]
    return math.sqrt(dot(e, e, w))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--weight", type=float, default=1.0)
    args = parser.parse_args()
    w = args.weight
    for run in args.runs:
        theta = {int(s["step"]): float(s["arc_length"])
                 for s in rows(os.path.join(run, "steps.csv")) if s["accepted"] == "true"}
        x = states(run)
        back = old = new = 0
        for k in range(2, len(x)):
            if x[k][0] != x[k - 1][0] + 1 or x[k][0] not in theta:
                continue
            th = theta[x[k][0]]
            if dot(sub(x[k][1], x[k - 1][1]), sub(x[k - 1][1], x[k - 2][1]), w) >= 0:
                continue
            back += 1
            last = distance(x[k][1], x[k - 2][1], x[k - 1][1], w)
            near, length, j = [], 0.0, k - 1
            while j >= 1 and length < 2 * th:
                near.append(distance(x[k][1], x[j - 1][1], x[j][1], w))
                seg = sub(x[j][1], x[j - 1][1])
                length += math.sqrt(dot(seg, seg, w))
                j -= 1
            if j == 0 and length < 2 * th:
                behind = [2 * a - b for a, b in zip(x[0][1], x[1][1])]
                near.append(distance(x[k][1], x[0][1], behind, w, ray=True))
            path = min(near)
            old += last <= 0.05 * th
            new += path <= 0.05 * th
            print(f"  {run} step {x[k][0]}: lambda {x[k][1][-1]:.6g}, theta {th:.4g}, backwards: "
                  f"{last / th:.3f} theta from the last segment, {path / th:.4f} theta from "
                  f"the traced path")
        print(f"{run}: {len(x) - 1} accepted states, {back} backwards; the last-segment guard "
              f"rejects {old}, a traced-path guard {new}")


if __name__ == "__main__":
    main()
