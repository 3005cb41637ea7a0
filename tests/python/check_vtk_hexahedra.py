#!/usr/bin/env python3
"""The VTK output of the 3-D solids, read by VTK's own readers (the ones ParaView uses):

    /usr/bin/python3 tests/python/check_vtk_hexahedra.py CONTACTBENCH_BINARY

runs `hertz-3d` on a 3 x 3 x 2 mesh and 10 steps of `plate-3d` (a state saved every 5) and checks,
for every .vtu of their .pvd collections: VTK reads it without an error; every cell is a
VTK_HEXAHEDRON (type 12); each hexahedron's corner order gives a positive Jacobian at all eight
corners (vtkMeshQuality), in the reference and in the deformed configuration (the points moved
by the `displacement` array); the point arrays `displacement` (3 components) and
`contact_reaction` and the cell array `von_mises_stress` are present with one tuple per point or
cell, finite; and every data set a .pvd lists exists and reads, its timesteps non-decreasing.

Exit status 0 when every check holds, 1 when one fails (each failure printed), and 77 (ctest's
SKIP_RETURN_CODE) when VTK's Python module is absent: Debian's python3-vtk9 provides it.
"""
import math
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError:
    print("skipped: VTK's Python module is absent (apt-get install python3-vtk9)")
    sys.exit(77)

VTK_HEXAHEDRON = 12
RUNS = {
    "hertz": ["--problem", "hertz-3d", "--set", "n=3", "--set", "nz=2"],
    "plate": ["--problem", "plate-3d", "--steps", "10", "--save-every", "5"],
}


class ErrorCatcher:
    """VTK's error and warning messages, collected instead of printed."""

    def __init__(self):
        self.messages = []
        self.window = vtk.vtkStringOutputWindow()
        vtk.vtkOutputWindow.SetInstance(self.window)

    def take(self):
        text = self.window.GetOutput().strip()
        self.window = vtk.vtkStringOutputWindow()
        vtk.vtkOutputWindow.SetInstance(self.window)
        return text


def read(path, catcher):
    reader = vtk.vtkXMLGenericDataObjectReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput(), reader.GetErrorCode(), catcher.take()


def min_corner_jacobian(grid):
    quality = vtk.vtkMeshQuality()
    quality.SetInputData(grid)
    quality.SetHexQualityMeasureToJacobian()
    quality.Update()
    values = vtk_to_numpy(quality.GetOutput().GetCellData().GetArray("Quality"))
    return float(values.min())


def deformed(grid):
    warp = vtk.vtkWarpVector()
    warp.SetInputData(grid)
    warp.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS,
                                "displacement")
    warp.SetScaleFactor(1.0)
    warp.Update()
    return warp.GetOutput()


def check_grid(path, grid, failures):
    name = os.path.basename(path)
    if grid.GetNumberOfCells() == 0:
        failures.append(f"{name}: no cells")
        return
    types = {grid.GetCellType(i) for i in range(grid.GetNumberOfCells())}
    if types != {VTK_HEXAHEDRON}:
        failures.append(f"{name}: cell types {sorted(types)}, not only {VTK_HEXAHEDRON}")
        return
    arrays = [("point", grid.GetPointData(), grid.GetNumberOfPoints(), "displacement", 3),
              ("point", grid.GetPointData(), grid.GetNumberOfPoints(), "contact_reaction", None),
              ("cell", grid.GetCellData(), grid.GetNumberOfCells(), "von_mises_stress", 1)]
    for kind, data, count, array_name, components in arrays:
        array = data.GetArray(array_name)
        if array is None:
            failures.append(f"{name}: no {kind} array {array_name}")
            continue
        if array.GetNumberOfTuples() != count:
            failures.append(f"{name}: {array_name} has {array.GetNumberOfTuples()} tuples, "
                            f"not {count}")
        if components is not None and array.GetNumberOfComponents() != components:
            failures.append(f"{name}: {array_name} has {array.GetNumberOfComponents()} "
                            f"components, not {components}")
        if not all(math.isfinite(v) for v in vtk_to_numpy(array).ravel()):
            failures.append(f"{name}: {array_name} has non-finite values")
    for configuration, g in (("reference", grid), ("deformed", deformed(grid))):
        jacobian = min_corner_jacobian(g)
        if not jacobian > 0.0:
            failures.append(f"{name}: a hexahedron with corner Jacobian {jacobian:g} <= 0 in "
                            f"the {configuration} configuration (corner order)")


def check_collection(pvd, catcher, failures):
    """Every data set of a .pvd: exists, reads without an error; .vtu ones checked as grids.
    Returns the number of hexahedral grids checked."""
    directory = os.path.dirname(pvd)
    times, grids = [], 0
    for entry in ElementTree.parse(pvd).getroot().iter("DataSet"):
        path = os.path.join(directory, entry.get("file"))
        times.append(float(entry.get("timestep")))
        if not os.path.isfile(path):
            failures.append(f"{os.path.basename(pvd)} lists {entry.get('file')}, absent")
            continue
        data, code, errors = read(path, catcher)
        if code != 0 or errors or data is None:
            failures.append(f"{os.path.basename(path)}: VTK cannot read it ({code}): {errors}")
            continue
        if path.endswith(".vtu"):
            check_grid(path, data, failures)
            grids += 1
    if times != sorted(times):
        failures.append(f"{os.path.basename(pvd)}: timesteps not in order: {times}")
    return grids


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    catcher = ErrorCatcher()
    failures = []
    with tempfile.TemporaryDirectory(prefix="contactbench_vtk_") as tmp:
        for label, args in RUNS.items():
            out = os.path.join(tmp, label)
            subprocess.run([argv[1], "run", *args, "--formulation", "implicit-fb", "--out", out],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            pvds = [os.path.join(out, "vtk", f) for f in os.listdir(os.path.join(out, "vtk"))
                    if f.endswith(".pvd")]
            if len(pvds) != 1:
                failures.append(f"{label}: {len(pvds)} .pvd files, not 1")
                continue
            grids = check_collection(pvds[0], catcher, failures)
            print(f"{label}: {grids} hexahedral grids read by VTK {vtk.vtkVersion.GetVTKVersion()}")
            if label == "plate" and grids < 2:
                failures.append(f"plate: {grids} saved states in the .pvd, expected several")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
