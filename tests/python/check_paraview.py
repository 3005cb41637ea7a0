#!/usr/bin/env python3
"""The VTK output opened as a ParaView user opens it: ParaView's own PVD reader, in pvpython.

    /usr/bin/python3 tests/python/check_paraview.py CONTACTBENCH_BINARY

runs a 2-D path (examples/q4-block-on-floor.json, a state saved every 10 steps) and a small
`hertz-3d`, opens each run's vtk/<problem>.pvd with paraview.simple.PVDReader and, at every time
it offers, fetches the data and reads every point, cell and field array of every block. Checks:
the times are the .pvd's (the reference state first, at 0, then increasing); each time has the
body and the obstacles; the body has `displacement` (3 components), `contact_reaction`, the cell
arrays `von_mises_stress` and `stress` (the Cauchy tensor, 9 components) under the same names in
2-D and 3-D, and the field data `lambda` and
`step` (0 and 0 at the reference, where the displacement is 0); the obstacles are one data set
with the cell array `obstacle` and the field data `id`; every array finite with one tuple per
point or cell.

Exit status 0 when every check holds, 1 when one fails (each printed), 77 (ctest's
SKIP_RETURN_CODE) when pvpython is absent (Debian's paraview package provides it).
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

RUNS = {
    "2-D": ["--problem-file", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                           "examples", "q4-block-on-floor.json"),
            "--save-every", "10"],
    "3-D": ["--problem", "hertz-3d", "--set", "n=3", "--set", "nz=2"],
}


def read_in_paraview(pvd):
    """Runs inside pvpython: every array of every leaf block at every time, as JSON."""
    from paraview import servermanager
    from paraview.simple import PVDReader
    reader = PVDReader(FileName=pvd)
    times = reader.TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    out = {"times": times, "states": []}
    for t in times:
        reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        blocks = []
        for b in range(data.GetNumberOfBlocks()):
            name = data.GetMetaData(b).Get(data.NAME()) if data.HasMetaData(b) else None
            blocks.append({"name": name, "leaves": [_leaf(x) for x in _leaves(data.GetBlock(b))]})
        out["states"].append({"time": t, "blocks": blocks})
    print(json.dumps(out))


def _leaves(block):
    if block is None:
        return []
    if block.IsA("vtkMultiBlockDataSet") or block.IsA("vtkMultiPieceDataSet"):
        return [leaf for k in range(block.GetNumberOfBlocks())
                for leaf in _leaves(block.GetBlock(k))]
    return [block]


def _leaf(data):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    leaf = {"class": data.GetClassName(), "points": data.GetNumberOfPoints(),
            "cells": data.GetNumberOfCells(), "arrays": {}}
    for kind, attributes in (("point", data.GetPointData()), ("cell", data.GetCellData()),
                             ("field", data.GetFieldData())):
        for i in range(attributes.GetNumberOfArrays()):
            array = attributes.GetAbstractArray(i)
            entry = {"tuples": array.GetNumberOfTuples(),
                     "components": array.GetNumberOfComponents()}
            if array.IsA("vtkDataArray"):
                values = vtk_to_numpy(array).ravel()
                entry["finite"] = bool(all(math.isfinite(float(v)) for v in values))
                entry["max_abs"] = float(max((abs(float(v)) for v in values), default=0.0))
                entry["first"] = float(values[0]) if len(values) else None
            leaf["arrays"][f"{kind}:{array.GetName()}"] = entry
    return leaf


def check_run(label, result, failures):
    times = result["times"]
    if not times or times[0] != 0.0 or times != sorted(set(times)) or len(times) < 2:
        failures.append(f"{label}: times {times}: not the reference at 0, then increasing")
    for state in result["states"]:
        where = f"{label} at time {state['time']:g}"
        leaves = {b["name"]: b["leaves"] for b in state["blocks"]}
        if len(state["blocks"]) != 2 or "obstacles" not in leaves:
            failures.append(f"{where}: blocks {list(leaves)}, not the body and the obstacles")
            continue
        body = [leaf for name, ls in leaves.items() if name != "obstacles" for leaf in ls]
        for leaf in body:
            check_arrays(where, leaf, {"point:displacement": 3, "point:contact_reaction": 1,
                                       "cell:von_mises_stress": 1, "cell:stress": 9,
                                       "field:lambda": 1,
                                       "field:step": 1}, failures)
            if state["time"] == 0.0:
                arrays = leaf["arrays"]
                for name in ("field:step", "field:lambda", "point:displacement"):
                    if arrays.get(name, {}).get("max_abs") != 0.0:
                        failures.append(f"{where}: {name} is not 0 in the reference state")
        obstacle_leaves = leaves["obstacles"]
        if len(obstacle_leaves) != 1:
            failures.append(f"{where}: the obstacles are {len(obstacle_leaves)} data sets, not 1")
        for leaf in obstacle_leaves:
            check_arrays(where + " (obstacles)", leaf, {"cell:obstacle": 1}, failures)
            if "field:id" not in leaf["arrays"]:
                failures.append(f"{where}: the obstacles carry no field data id")


def check_arrays(where, leaf, expected, failures):
    counts = {"point": leaf["points"], "cell": leaf["cells"], "field": 1}
    for name, components in expected.items():
        if name not in leaf["arrays"]:
            failures.append(f"{where}: no array {name} (has {sorted(leaf['arrays'])})")
    for name, entry in leaf["arrays"].items():
        kind = name.split(":")[0]
        if kind != "field" and entry["tuples"] != counts[kind]:
            failures.append(f"{where}: {name} has {entry['tuples']} tuples, not {counts[kind]}")
        if name in expected and entry["components"] != expected[name]:
            failures.append(f"{where}: {name} has {entry['components']} components")
        if entry.get("finite") is False:
            failures.append(f"{where}: {name} has non-finite values")


def main(argv):
    if len(argv) == 3 and argv[1] == "--read":
        read_in_paraview(argv[2])
        return 0
    if len(argv) != 2:
        print(__doc__)
        return 2
    pvpython = shutil.which("pvpython")
    if pvpython is None:
        print("skipped: pvpython is absent (apt-get install paraview)")
        return 77
    failures = []
    with tempfile.TemporaryDirectory(prefix="contactbench_paraview_") as tmp:
        for label, args in RUNS.items():
            out = os.path.join(tmp, label)
            subprocess.run([argv[1], "run", *args, "--formulation", "implicit-fb", "--out", out],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            pvd = [f for f in os.listdir(os.path.join(out, "vtk")) if f.endswith(".pvd")][0]
            read = subprocess.run([pvpython, "--force-offscreen-rendering",
                                   os.path.abspath(__file__), "--read",
                                   os.path.join(out, "vtk", pvd)],
                                  capture_output=True, text=True)
            if read.returncode != 0:
                failures.append(f"{label}: pvpython failed: {read.stderr.strip()[-2000:]}")
                continue
            result = json.loads(read.stdout.strip().splitlines()[-1])
            check_run(label, result, failures)
            print(f"{label}: {len(result['times'])} times read by ParaView's PVD reader")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
