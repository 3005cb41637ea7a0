#include "harness/vtk_files.h"

#include <filesystem>
#include <numeric>
#include <sstream>
#include <tuple>
#include <utility>

#include "core/csv.h"
#include "core/owned_file.h"

namespace cb::harness {

namespace {

// VTK cell types of the XML formats.
constexpr int kVtkLine = 3;
constexpr int kVtkTriangle = 5;
constexpr int kVtkQuad = 9;
constexpr int kVtkTetra = 10;
constexpr int kVtkHexahedron = 12;
// vtkDataSetAttributes::DUPLICATEPOINT: a point another piece owns.
constexpr int kVtkDuplicatePoint = 1;

// The VTK type of an element of `corners` nodes in a body of dimension `dim` (0: unknown).
int VtkCellType(std::size_t corners, int dim) {
  switch (corners) {
    case 2:
      return kVtkLine;
    case 3:
      return kVtkTriangle;
    case 4:
      return dim == 3 ? kVtkTetra : kVtkQuad;
    case 8:
      return kVtkHexahedron;
    default:
      return 0;
  }
}

// Writes the text composed in `out` as the file `path`, never through a symbolic link
// (core/owned_file.h); a file cut short is removed.
void WriteWhole(const std::ostringstream& out, const std::string& path) {
  WriteOwnedFile(path, out.str(), FileCreation::kReplace);
}

// The text of one file, composed in memory and written whole by WriteWhole.
std::ostringstream Open() {
  std::ostringstream out;
  out.precision(17);
  return out;
}

void WriteConnectivity(std::ostringstream& out, const std::vector<std::vector<int>>& cells) {
  out << "        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n         ";
  for (const auto& cell : cells) {
    for (int n : cell) out << ' ' << n;
  }
  out << "\n        </DataArray>\n"
      << "        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n         ";
  int offset = 0;
  for (const auto& cell : cells) out << ' ' << (offset += static_cast<int>(cell.size()));
  out << "\n        </DataArray>\n";
}

}  // namespace

std::string XmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

// The points and cells a .vtu holds: `nodes`, the body's node of each point; `cells`, the
// body's elements (indices in the order of Cells()); with `piece`, also the arrays that place
// them in the whole body (global_point, global_cell, vtkGhostType).
struct GridSelection {
  const std::vector<int>& nodes;
  const std::vector<int>& cells;
  const BodyPiece* piece;
};

// The NumberOfComponents attribute of an array of `components` (none for 1).
std::string Components(int components) {
  return components == 1 ? "" : " NumberOfComponents=\"" + std::to_string(components) + "\"";
}

// The attributes that make the first scalar field and the first tensor ParaView's defaults.
std::string ActiveArrays(const std::vector<CellField>& fields) {
  std::string scalars, tensors;
  for (const CellField& f : fields) {
    if (f.components == 1 && scalars.empty()) scalars = " Scalars=\"" + XmlEscaped(f.name) + "\"";
    if (f.components == 9 && tensors.empty()) tensors = " Tensors=\"" + XmlEscaped(f.name) + "\"";
  }
  return scalars + tensors;
}

void WriteIndices(std::ostringstream& out, const char* name, const std::vector<int>& indices) {
  out << "        <DataArray type=\"Int64\" Name=\"" << name << "\" format=\"ascii\">\n         ";
  for (int i : indices) out << ' ' << i;
  out << "\n        </DataArray>\n";
}

// The grid's cells, their nodes renumbered to the grid's points when it is a piece.
std::vector<std::vector<int>> GridCells(const ElasticBody& body, const GridSelection& grid) {
  const std::vector<std::vector<int>> all_cells = body.Cells();
  const bool whole = grid.piece == nullptr;
  // The point of each node in this grid (-1: not in it).
  std::vector<int> point_of(whole ? 0 : body.num_nodes(), -1);
  for (std::size_t k = 0; k < grid.nodes.size() && !whole; ++k) {
    point_of[grid.nodes[k]] = static_cast<int>(k);
  }
  std::vector<std::vector<int>> cells;
  cells.reserve(grid.cells.size());
  for (int c : grid.cells) {
    cells.push_back(all_cells[c]);
    if (!whole) {
      for (int& node : cells.back()) node = point_of[node];
    }
  }
  return cells;
}

// The header, the step's lambda and number as field data, and the piece's opening tag.
void WriteGridHeader(std::ostringstream& out, const State& state, int step, std::size_t points,
                     std::size_t cells) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"lambda\" NumberOfTuples=\"1\" format=\"ascii\">"
      << state.lambda << "</DataArray>\n"
      << "      <DataArray type=\"Int32\" Name=\"step\" NumberOfTuples=\"1\" format=\"ascii\">"
      << step << "</DataArray>\n"
      << "    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << points << "\" NumberOfCells=\"" << cells << "\">\n";
}

// The reference points (3 components, zero beyond the body's dimension), then the cells.
void WritePointsAndCells(std::ostringstream& out, const ElasticBody& body,
                         const std::vector<int>& nodes,
                         const std::vector<std::vector<int>>& cells) {
  const int dim = body.dim();
  out << "      <Points>\n"
      << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (int n : nodes) {
    const Point x = body.reference(n);
    out << "         ";
    for (int c = 0; c < 3; ++c) out << ' ' << (c < dim ? x[c] : 0.0);
    out << '\n';
  }
  out << "        </DataArray>\n      </Points>\n      <Cells>\n";
  WriteConnectivity(out, cells);
  out << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n         ";
  for (const auto& cell : cells) out << ' ' << VtkCellType(cell.size(), dim);
  out << "\n        </DataArray>\n      </Cells>\n";
}

// Per point: the displacement and the contact reaction summed over the node's pairs; in a
// piece also the global point number and which points are another piece's (ghosts).
void WritePointData(std::ostringstream& out, const BodyContactModel& model, const State& state,
                    const GridSelection& grid) {
  const ElasticBody& body = model.body();
  const int dim = body.dim();
  std::vector<double> reaction(body.num_nodes(), 0.0);
  for (int p = 0; p < model.num_pairs(); ++p) reaction[model.pairs()[p].node] += state.r[p];
  out << "      <PointData Vectors=\"displacement\" Scalars=\"contact_reaction\">\n"
      << "        <DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (int n : grid.nodes) {
    const Point x = body.reference(n);
    const Point moved = body.Position(n, state.u);
    out << "         ";
    for (int c = 0; c < 3; ++c) out << ' ' << (c < dim ? moved[c] - x[c] : 0.0);
    out << '\n';
  }
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Float64\" Name=\"contact_reaction\" format=\"ascii\">\n";
  for (int n : grid.nodes) out << "          " << reaction[n] << '\n';
  out << "        </DataArray>\n";
  if (grid.piece != nullptr) {
    WriteIndices(out, "global_point", grid.nodes);
    out << "        <DataArray type=\"UInt8\" Name=\"vtkGhostType\" format=\"ascii\">\n         ";
    for (bool duplicate : grid.piece->duplicate) out << ' ' << (duplicate ? kVtkDuplicatePoint : 0);
    out << "\n        </DataArray>\n";
  }
  out << "      </PointData>\n";
}

// Per cell: the body's cell fields (stresses); in a piece also the global cell number.
void WriteCellData(std::ostringstream& out, const ElasticBody& body, const State& state,
                   const GridSelection& grid) {
  const bool whole = grid.piece == nullptr;
  const std::vector<CellField> fields =
      whole ? body.CellFields(state.u) : body.Restricted(grid.cells)->CellFields(state.u);
  out << "      <CellData" << ActiveArrays(fields) << ">\n";
  for (const CellField& field : fields) {
    out << "        <DataArray type=\"Float64\" Name=\"" << XmlEscaped(field.name) << "\""
        << Components(field.components) << " format=\"ascii\">\n         ";
    for (double v : field.values) out << ' ' << v;
    out << "\n        </DataArray>\n";
  }
  if (!whole) WriteIndices(out, "global_cell", grid.cells);
  out << "      </CellData>\n";
}

void WriteGrid(const std::string& path, const Problem& problem, const State& state, int step,
               const GridSelection& grid) {
  const BodyContactModel& model = *problem.body;
  const ElasticBody& body = model.body();
  const std::vector<std::vector<int>> cells = GridCells(body, grid);
  std::ostringstream out = Open();
  WriteGridHeader(out, state, step, grid.nodes.size(), cells.size());
  WritePointsAndCells(out, body, grid.nodes, cells);
  WritePointData(out, model, state, grid);
  WriteCellData(out, body, state, grid);
  out << "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  WriteWhole(out, path);
}

}  // namespace

void WriteBodyVtu(const std::string& path, const Problem& problem, const State& state, int step) {
  const ElasticBody& body = problem.body->body();
  std::vector<int> nodes(static_cast<std::size_t>(body.num_nodes()));
  std::iota(nodes.begin(), nodes.end(), 0);
  std::vector<int> cells(body.Cells().size());
  std::iota(cells.begin(), cells.end(), 0);
  WriteGrid(path, problem, state, step, {nodes, cells, nullptr});
}

void WriteBodyPieceVtu(const std::string& path, const Problem& problem, const State& state,
                       int step, const BodyPiece& piece) {
  WriteGrid(path, problem, state, step, {piece.nodes, piece.cells, &piece});
}

void WriteBodyPvtu(const std::string& path, const std::vector<CellField>& cell_fields,
                   const std::vector<std::string>& pieces) {
  std::ostringstream out = Open();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
      << "    <PPointData Vectors=\"displacement\" Scalars=\"contact_reaction\">\n"
      << "      <PDataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\"/>\n"
      << "      <PDataArray type=\"Float64\" Name=\"contact_reaction\"/>\n"
      << "      <PDataArray type=\"Int64\" Name=\"global_point\"/>\n"
      << "      <PDataArray type=\"UInt8\" Name=\"vtkGhostType\"/>\n"
      << "    </PPointData>\n"
      << "    <PCellData" << ActiveArrays(cell_fields) << ">\n";
  for (const CellField& field : cell_fields) {
    out << "      <PDataArray type=\"Float64\" Name=\"" << XmlEscaped(field.name) << "\""
        << Components(field.components) << "/>\n";
  }
  out << "      <PDataArray type=\"Int64\" Name=\"global_cell\"/>\n"
      << "    </PCellData>\n"
      << "    <PPoints>\n"
      << "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
      << "    </PPoints>\n";
  for (const std::string& piece : pieces) {
    out << "    <Piece Source=\"" << XmlEscaped(piece) << "\"/>\n";
  }
  out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  WriteWhole(out, path);
}

namespace {

// The surfaces as one: their points and cells appended in turn, and the surface each line and
// each polygon comes from (in VTK's cell order: every line, then every polygon).
struct MergedSurfaces {
  SurfaceGeometry all;
  std::vector<int> line_of, polygon_of;
};

MergedSurfaces Merged(const std::vector<SurfaceGeometry>& surfaces) {
  MergedSurfaces m;
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const int offset = static_cast<int>(m.all.points.size());
    const SurfaceGeometry& s = surfaces[k];
    m.all.points.insert(m.all.points.end(), s.points.begin(), s.points.end());
    for (const auto& [cells, of, into] :
         {std::tuple(&s.lines, &m.line_of, &m.all.lines),
          std::tuple(&s.polygons, &m.polygon_of, &m.all.polygons)}) {
      for (std::vector<int> cell : *cells) {
        for (int& point : cell) point += offset;
        into->push_back(std::move(cell));
        of->push_back(static_cast<int>(k));
      }
    }
  }
  return m;
}

// VTK's ASCII strings: the byte values of each, each string ended by a 0.
void WriteStrings(std::ostringstream& out, const std::vector<std::string>& strings) {
  for (const std::string& text : strings) {
    for (unsigned char c : text) out << static_cast<int>(c) << ' ';
    out << "0 ";
  }
}

}  // namespace

void WriteObstaclesVtp(const std::string& path, const std::vector<SurfaceGeometry>& surfaces,
                       const std::vector<std::string>& ids) {
  const MergedSurfaces m = Merged(surfaces);
  std::ostringstream out = Open();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <PolyData>\n"
      << "    <FieldData>\n"
      << "      <Array type=\"String\" Name=\"id\" NumberOfTuples=\"" << ids.size()
      << "\" format=\"ascii\">";
  WriteStrings(out, ids);
  out << "</Array>\n"
      << "    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << m.all.points.size() << "\" NumberOfVerts=\"0\" "
      << "NumberOfLines=\"" << m.all.lines.size() << "\" NumberOfStrips=\"0\" "
      << "NumberOfPolys=\"" << m.all.polygons.size() << "\">\n"
      << "      <Points>\n"
      << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Point3& p : m.all.points) {
    out << "          " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  }
  out << "        </DataArray>\n      </Points>\n";
  if (!m.all.lines.empty()) {
    out << "      <Lines>\n";
    WriteConnectivity(out, m.all.lines);
    out << "      </Lines>\n";
  }
  if (!m.all.polygons.empty()) {
    out << "      <Polys>\n";
    WriteConnectivity(out, m.all.polygons);
    out << "      </Polys>\n";
  }
  out << "      <CellData Scalars=\"obstacle\">\n"
      << "        <DataArray type=\"Int32\" Name=\"obstacle\" format=\"ascii\">\n         ";
  for (const std::vector<int>* of : {&m.line_of, &m.polygon_of}) {
    for (int k : *of) out << ' ' << k;
  }
  out << "\n        </DataArray>\n      </CellData>\n"
      << "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  WriteWhole(out, path);
}

void WritePvd(const std::string& path, const std::vector<PvdDataSet>& datasets) {
  const std::string temporary = path + ".tmp";
  {
    std::ostringstream out = Open();
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const PvdDataSet& d : datasets) {
      out << "    <DataSet timestep=\"" << d.timestep << "\" group=\"\" part=\"" << d.part
          << "\" name=\"" << XmlEscaped(d.name) << "\" file=\"" << XmlEscaped(d.file) << "\"/>";
      if (!d.comment.empty()) out << "  <!-- " << XmlEscaped(d.comment) << " -->";
      out << '\n';
    }
    out << "  </Collection>\n</VTKFile>\n";
    WriteWhole(out, temporary);
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);  // atomic: never a half-written collection
  if (ec) throw WriteError(path, "cannot rename '" + temporary + "' to it: " + ec.message());
}

}  // namespace cb::harness
