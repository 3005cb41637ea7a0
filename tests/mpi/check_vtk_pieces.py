#!/usr/bin/env python3
"""A distributed run's VTK output, one piece per process and a parallel index, read by VTK's own
readers (the ones ParaView uses):

    /usr/bin/python3 tests/mpi/check_vtk_pieces.py CONTACTBENCH MPIEXEC WORK_DIR

runs P1 (block, n = 8, every state saved) serially with implicit-fb, with dist-implicit-fb in
one process, and with dist-implicit-fb on two processes (mpirun -n 2, root-safe), then checks:
the one-process run writes whole-body .vtu files as a serial run does (no .pvtu, no piece); the
two-process collection (.pvd) lists a .pvtu at each of the serial collection's times; for every
state the serial run saved (block_NNNN.vtu) the two-process run wrote block_NNNN.pvtu, which
reads without an error or warning (VTK's vtkXMLGenericDataObjectReader, which dispatches to
vtkXMLPUnstructuredGridReader) as an unstructured grid and references one piece per process;
its cells are the serial file's, each once (global_cell), and its points
each of the serial file's once where not marked a duplicate (vtkGhostType), every duplicate a
copy of an owned point; the points, the displacement, the contact reactions and the cell data
equal the serial run's at their global indices (the displacement to 1e-10, the others to 1e-8
of their largest magnitude). Last, a two-process run whose process 1 cannot write its piece
(a file size limit of 512 bytes on that process alone) must end, not hang, as a failed run
(run.json: exit status 3, the reason naming process 1) with no index of the unwritten piece.

Exit status 0 when every check holds, 1 when one fails (each failure printed), and 77 (ctest's
SKIP_RETURN_CODE) when VTK's Python module is absent: Debian's python3-vtk9 provides it.
"""
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

# VTK's readers with their messages collected (and the skip without VTK): the 3-D output test's.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from check_vtk_hexahedra import ErrorCatcher, read  # noqa: E402 (exits 77 without VTK)

import numpy  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

PROBLEM = ["--problem", "block", "--set", "n=8", "--save-every", "1"]
DUPLICATE_POINT = 1  # vtkDataSetAttributes::DUPLICATEPOINT
CELL_FIELDS = ["stress_xx", "stress_yy", "stress_xy", "von_mises_stress"]


def run(command, log):
    with open(log, "w") as out:
        status = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT).returncode
    if status != 0:
        with open(log) as f:
            sys.stdout.write(f.read())
        sys.exit(f"failed (status {status}): {' '.join(command)}")


def collection(directory):
    """The (timestep, file) of the body's datasets (part 0) of the run's .pvd."""
    root = ElementTree.parse(os.path.join(directory, "vtk", "block.pvd")).getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")
            if d.get("part") == "0"]


def array(data, name):
    found = data.GetArray(name)
    return None if found is None else vtk_to_numpy(found)


def close(a, b, tolerance):
    return a.shape == b.shape and numpy.abs(a - b).max(initial=0.0) <= tolerance


def check_state(serial_path, pvtu_path, errors, failures):
    name = os.path.basename(pvtu_path)
    serial, code, message = read(serial_path, errors)
    if code != 0 or message:
        failures.append(f"{serial_path}: the serial file does not read ({message})")
        return
    grid, code, message = read(pvtu_path, errors)
    if code != 0 or message:
        failures.append(f"{name}: VTK reports {message or f'error code {code}'}")
        return
    if not isinstance(grid, vtk.vtkUnstructuredGrid):
        failures.append(f"{name}: read as {grid.GetClassName()}, not an unstructured grid")
        return
    pieces = [p.get("Source") for p in ElementTree.parse(pvtu_path).getroot().iter("Piece")]
    if len(pieces) != 2:
        failures.append(f"{name}: pieces {pieces} for 2 processes")
    cells = array(grid.GetCellData(), "global_cell")
    points = array(grid.GetPointData(), "global_point")
    ghost = array(grid.GetPointData(), "vtkGhostType")
    if cells is None or points is None or ghost is None:
        failures.append(f"{name}: global_cell, global_point or vtkGhostType missing")
        return
    owned = points[ghost != DUPLICATE_POINT]
    if grid.GetNumberOfCells() != serial.GetNumberOfCells() or \
            sorted(cells) != list(range(serial.GetNumberOfCells())):
        failures.append(f"{name}: {grid.GetNumberOfCells()} cells, not each of the serial "
                        f"file's {serial.GetNumberOfCells()} once")
    if len(owned) != serial.GetNumberOfPoints() or \
            sorted(owned) != list(range(serial.GetNumberOfPoints())):
        failures.append(f"{name}: {len(owned)} points not marked duplicates, not each of the "
                        f"serial file's {serial.GetNumberOfPoints()} once")
        return
    if set(points) != set(owned):
        failures.append(f"{name}: a duplicate point without an owner's point")
    # Every point (duplicates included) against the serial file's point of its global index.
    at = points.astype(int)
    references = vtk_to_numpy(grid.GetPoints().GetData())
    if not close(references, vtk_to_numpy(serial.GetPoints().GetData())[at], 0.0):
        failures.append(f"{name}: a point is not at its serial place")
    u, u_serial = (array(g.GetPointData(), "displacement") for g in (grid, serial))
    if u is None or not close(u, u_serial[at], 1e-10):
        failures.append(f"{name}: displacement differs from the serial run's by more than 1e-10")
        return
    fields = [("contact_reaction", grid.GetPointData(), serial.GetPointData(), at)]
    fields += [(f, grid.GetCellData(), serial.GetCellData(), cells.astype(int))
               for f in CELL_FIELDS]
    for field, data, serial_data, index in fields:
        values, expected = array(data, field), array(serial_data, field)
        if values is None or expected is None:
            failures.append(f"{name}: {field} missing")
            continue
        scale = max(1.0, float(numpy.abs(expected).max(initial=0.0)))
        if not close(values, expected[index], 1e-8 * scale):
            failures.append(f"{name}: {field} differs from the serial run's")
    print(f"{name}: displacement within {numpy.abs(u - u_serial[at]).max():.1e} of the serial "
          f"run's; {grid.GetNumberOfCells()} cells, {len(owned)} points "
          f"({len(points) - len(owned)} duplicates), as the serial file")


def check_failed_piece(binary, mpiexec, out, failures):
    run_args = [binary, "run", *PROBLEM, "--formulation", "dist-implicit-fb", "--out", out]
    limited = ["/bin/sh", "-c", 'ulimit -f 1 && exec "$0" "$@"', *run_args]
    try:
        status = subprocess.run([mpiexec, "-n", "1", *run_args, ":", "-n", "1", *limited],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                timeout=300).returncode
    except subprocess.TimeoutExpired:
        failures.append("a piece that cannot be written: the run hung")
        return
    with open(os.path.join(out, "run.json")) as f:
        record = json.load(f)
    if status == 0 or record.get("exit_status") != 3 or \
            "process 1" not in record.get("reason", ""):
        failures.append(f"a piece that cannot be written: status {status}, run.json "
                        f"{record.get('exit_status')} '{record.get('reason')}'")
    if any(f.endswith(".pvtu") for f in os.listdir(os.path.join(out, "vtk"))):
        failures.append("a piece that cannot be written: an index was written")
    print(f"process 1 without its piece: status {status}, '{record.get('reason')}'")


def main():
    binary, mpiexec, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.environ.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                      OMPI_MCA_rmaps_base_oversubscribe="1")
    out = {label: os.path.join(work, label) for label in ("serial", "one", "two")}
    run([binary, "run", *PROBLEM, "--formulation", "implicit-fb", "--out", out["serial"]],
        out["serial"] + ".log")
    run([binary, "run", *PROBLEM, "--formulation", "dist-implicit-fb", "--out", out["one"]],
        out["one"] + ".log")
    run([mpiexec, "-n", "2", binary, "run", *PROBLEM, "--formulation", "dist-implicit-fb",
         "--out", out["two"]], out["two"] + ".log")

    failures = []
    serial_states = collection(out["serial"])
    one_files = sorted(os.listdir(os.path.join(out["one"], "vtk")))
    if one_files != sorted(os.listdir(os.path.join(out["serial"], "vtk"))) or \
            collection(out["one"]) != serial_states:
        failures.append(f"one process: {one_files}, not the serial run's files")
    two_states = collection(out["two"])
    if [t for t, _ in two_states] != [t for t, _ in serial_states] or \
            not all(f.endswith(".pvtu") for _, f in two_states):
        failures.append(f"two processes: the collection lists {two_states}, not one .pvtu at "
                        f"each of the serial run's times {serial_states}")
    if len(serial_states) < 1:
        failures.append("the serial run saved no state")
    errors = ErrorCatcher()
    # Every saved state, the collection's and those a later save at the same time replaced.
    serial_files = sorted(f for f in os.listdir(os.path.join(out["serial"], "vtk"))
                          if f.endswith(".vtu"))
    for serial_file in serial_files:
        pvtu = os.path.join(out["two"], "vtk", serial_file[:-len(".vtu")] + ".pvtu")
        if not os.path.exists(pvtu):
            failures.append(f"two processes: no {os.path.basename(pvtu)}")
            continue
        check_state(os.path.join(out["serial"], "vtk", serial_file), pvtu, errors, failures)
    check_failed_piece(binary, mpiexec, os.path.join(work, "failed"), failures)
    for failure in failures:
        print("FAILED: " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
