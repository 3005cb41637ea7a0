// The VTK XML files of the saved states (ASCII, so that they diff and open anywhere): the body
// at a state as an unstructured grid (.vtu) or, in a distributed run, as pieces (.vtu) with
// their parallel index (.pvtu), an obstacle's surface as poly data (.vtp), and the collection
// (.pvd) that ParaView opens. Each file is written whole or removed: a VTK file
// cut short is no VTK file.
#pragma once

#include <string>
#include <vector>

#include "harness/obstacle_geometry.h"
#include "problems/problem.h"

namespace cb::harness {

// `text` made safe in an XML attribute or comment.
std::string XmlEscaped(const std::string& text);

// The body of `problem` at `state` (step `step`): reference points; the elements as cells; as
// point data the displacement (3 components, for "Warp By Vector") and the sum of the contact
// reactions at each node; as cell data the body's CellFields; lambda and step as field data.
void WriteBodyVtu(const std::string& path, const Problem& problem, const State& state, int step);

// A part of the body: the elements `cells` (indices in the order of ElasticBody::Cells()) and
// the nodes `nodes` (ascending) its points are, those of its cells among them; `duplicate`, one
// per node, marks a node another piece owns (each node has exactly one owner).
struct BodyPiece {
  std::vector<int> nodes;
  std::vector<int> cells;
  std::vector<bool> duplicate;
};

// The piece of the body at `state`: as WriteBodyVtu for its points and cells, the cell data
// those of its elements, and three arrays that place it in the whole body: global_point (the
// node of each point, the point's index in WriteBodyVtu's file), global_cell (likewise for
// each cell) and vtkGhostType (1, VTK's DUPLICATEPOINT, where `duplicate`), so that the pieces
// of an index hold every point of the body once without the duplicates.
void WriteBodyPieceVtu(const std::string& path, const Problem& problem, const State& state,
                       int step, const BodyPiece& piece);

// The parallel index (.pvtu, VTK's PUnstructuredGrid) of the pieces `pieces` (paths relative to
// it) that WriteBodyPieceVtu wrote, whose cell data are `cell_fields`.
void WriteBodyPvtu(const std::string& path, const std::vector<CellField>& cell_fields,
                   const std::vector<std::string>& pieces);

// The obstacles of a problem as one poly data set: each surface's points and cells appended in
// turn, the cell array `obstacle` the index of the surface a cell belongs to, and the field data
// `id` the obstacles' ids (one string per obstacle, in the order of `surfaces`).
void WriteObstaclesVtp(const std::string& path, const std::vector<SurfaceGeometry>& surfaces,
                       const std::vector<std::string>& ids);

// One dataset of a collection: at time `timestep`, block `part` (named `name`), from `file`
// (relative to the .pvd); `comment` is written beside it.
struct PvdDataSet {
  double timestep = 0.0;
  int part = 0;
  std::string name;
  std::string file;
  std::string comment;
};

// The collection, written to a temporary file renamed into place: never half written.
void WritePvd(const std::string& path, const std::vector<PvdDataSet>& datasets);

}  // namespace cb::harness
