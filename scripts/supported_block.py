#!/usr/bin/env python3
"""Writes a plane-stress Q4 problem file of an n x n block with supports, for the multigrid
measurements of docs/scale-out.md ("Multigrid with supports").

floor: a W x W block on a frictionless floor under a top pressure, one bottom node held in x
       (uniform stress: uy = -p y / E, ux = nu p (x - x0) / E);
p1:    P1's block (side 2, E = 1e8, nu = 0.3, thickness 0.01, traction (-5e5, -5e5) on the right
       edge, against a wall x >= 0 and a floor y >= 0) with the top-left node held in x.

usage: supported_block.py floor|p1 N OUT.json
"""
import json
import sys


def block(kind, n):
    side = 2.0 if kind == "p1" else 1.0
    h = side / n
    node_id = lambda i, j: j * (n + 1) + i + 1  # noqa: E731
    nodes = [{"id": node_id(i, j), "x": [i * h, j * h]}
             for j in range(n + 1) for i in range(n + 1)]
    elements = [{"nodes": [node_id(i, j), node_id(i + 1, j), node_id(i + 1, j + 1),
                           node_id(i, j + 1)]}
                for j in range(n) for i in range(n)]
    bottom = [node_id(i, 0) for i in range(n + 1)]
    left = [node_id(0, j) for j in range(n + 1)]
    problem = {"kind": "plane-stress-q4", "version": 1, "units": "consistent units",
               "deformation": "small", "nodes": nodes, "elements": elements,
               "analysis": "fixed-load", "load": 1.0}
    if kind == "floor":
        top = [[node_id(i, n), node_id(i + 1, n)] for i in range(n)]
        problem.update({
            "name": f"supported-floor-n{n}",
            "description": "n x n Q4 block on a floor, top pressure, one node held in x",
            "thickness": 0.1, "material": {"E": 1000.0, "nu": 0.25},
            "supports": [{"node": node_id(n // 2, 0), "fixed": ["x"]}],
            "tractions": [{"edges": top, "traction": [0.0, -10.0]}],
            "obstacles": [{"id": "floor", "type": "half-space", "point": [0.0, 0.0],
                           "normal": [0.0, -1.0]}],
            "contact_pairs": [{"node": k, "obstacle": "floor"} for k in bottom],
            "length_scale": 0.01, "force_scale": 1.0,
            "control": {"node": node_id(n, n), "direction": "y", "label": "top-right uy"}})
    else:
        right = [[node_id(n, j), node_id(n, j + 1)] for j in range(n)]
        problem.update({
            "name": f"p1-supported-n{n}",
            "description": "P1's block with the top-left node held in x",
            "thickness": 0.01, "material": {"E": 1e8, "nu": 0.3},
            "supports": [{"node": node_id(0, n), "fixed": ["x"]}],
            "tractions": [{"edges": right, "traction": [-5e5, -5e5]}],
            "obstacles": [{"id": "floor", "type": "half-space", "point": [0.0, 0.0],
                           "normal": [0.0, -1.0]},
                          {"id": "wall", "type": "half-space", "point": [0.0, 0.0],
                           "normal": [-1.0, 0.0]}],
            "contact_pairs": [{"node": k, "obstacle": "floor"} for k in bottom]
            + [{"node": k, "obstacle": "wall"} for k in left[:-1]],
            "length_scale": 0.01, "force_scale": 100.0,
            "control": {"node": node_id(n, n), "direction": "y", "label": "top-right uy"}})
    return problem


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("floor", "p1") or not sys.argv[2].isdigit():
        sys.exit(__doc__)
    with open(sys.argv[3], "w") as out:
        json.dump(block(sys.argv[1], int(sys.argv[2])), out)


if __name__ == "__main__":
    main()
