"""The obstacles of a run, as the run wrote them (vtk/*obstacle*.vtp, one file per obstacle),
and their drawing into a figure of the deformed shape (2-D or 3-D axes)."""
import glob
import os
import xml.etree.ElementTree as ElementTree

import numpy as np

COLOUR = "tab:red"
GID = "obstacle"  # the artists' group id: figures and tests find the obstacles by it


def read(run_dir):
    """The obstacles' geometry from the VTK files the run wrote: a list of (name, points (n x 3),
    polylines (lists of point indices)); empty when the run wrote none."""
    obstacles = []
    for path in sorted(glob.glob(os.path.join(run_dir, "vtk", "*obstacle*.vtp"))):
        root = ElementTree.parse(path).getroot()
        piece = root.find("./PolyData/Piece")
        if piece is None:
            continue
        points = np.array(piece.find("./Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
        lines = []
        for kind in ("Lines", "Polys"):
            block = piece.find(kind)
            if block is None:
                continue
            arrays = {a.get("Name"): np.array(a.text.split(), dtype=int)
                      for a in block.findall("DataArray")}
            start = 0
            for end in arrays["offsets"]:
                cell = list(arrays["connectivity"][start:end])
                lines.append(cell + cell[:1] if kind == "Polys" else cell)
                start = end
        name = os.path.splitext(os.path.basename(path))[0]
        obstacles.append((name, points, lines))
    return obstacles


def draw(ax, obstacles, three_d=False, label="obstacles", colour=COLOUR):
    """Every polyline of every obstacle, in one colour; the first carries `label` (legend)."""
    for name, points, lines in obstacles:
        for line in lines:
            xyz = points[line]
            ax.plot(*(xyz[:, :3].T if three_d else xyz[:, :2].T), color=colour, lw=1.4,
                    gid=GID, label=label)
            label = None


def faces(obstacles):
    """Every closed polyline of the obstacles (their polygons) as an array of points each."""
    return [points[line[:-1]] for _, points, lines in obstacles for line in lines
            if len(line) > 3 and line[0] == line[-1]]


def draw_3d(ax, obstacles, low, high, colour=COLOUR):
    """The obstacles' faces that reach into the window [low, high] as one Poly3DCollection
    (an obstacle of many planes is one artist, not one per plane), the points outside the window
    pulled onto its sides so that a large surface does not set the axes; open polylines as one
    Line3DCollection. Returns the artists added."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection
    inside = [np.clip(f, low, high) for f in faces(obstacles)
              if np.all(f.max(axis=0) >= low) and np.all(f.min(axis=0) <= high)]
    open_lines = [np.clip(points[line], low, high) for _, points, lines in obstacles
                  for line in lines if not (len(line) > 3 and line[0] == line[-1])]
    added = []
    if inside:
        polys = Poly3DCollection(inside, facecolors=colour, edgecolors="none", alpha=0.25)
        polys.set_gid(GID)
        added.append(ax.add_collection3d(polys) or polys)
    if open_lines:
        lines = Line3DCollection(open_lines, colors=colour, linewidths=1.0)
        lines.set_gid(GID)
        added.append(ax.add_collection3d(lines) or lines)
    return added
