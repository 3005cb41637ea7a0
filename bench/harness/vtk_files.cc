#include "harness/vtk_files.h"

#include <filesystem>
#include <fstream>

#include "core/csv.h"

namespace cb::harness {

namespace {

// VTK cell types of the XML formats.
constexpr int kVtkLine = 3;
constexpr int kVtkTriangle = 5;
constexpr int kVtkQuad = 9;
constexpr int kVtkTetra = 10;
constexpr int kVtkHexahedron = 12;

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

// Closes `out` (which flushes it) and checks every write; a file cut short is removed.
void CloseOrRemove(std::ofstream& out, const std::string& path) {
  out.close();
  if (out) return;
  std::error_code ec;
  std::filesystem::remove(path, ec);
  throw WriteError(path, "the write failed (disk full?); the file was removed");
}

std::ofstream Open(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw WriteError(path, "cannot open it");
  out.precision(17);
  return out;
}

void WriteConnectivity(std::ofstream& out, const std::vector<std::vector<int>>& cells) {
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

void WriteBodyVtu(const std::string& path, const Problem& problem, const State& state, int step) {
  const BodyContactModel& model = *problem.body;
  const ElasticBody& body = model.body();
  const int dim = body.dim();
  const std::vector<std::vector<int>> cells = body.Cells();
  std::vector<double> reaction(body.num_nodes(), 0.0);
  for (int p = 0; p < model.num_pairs(); ++p) reaction[model.pairs()[p].node] += state.r[p];

  std::ofstream out = Open(path);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"lambda\" NumberOfTuples=\"1\" format=\"ascii\">"
      << state.lambda << "</DataArray>\n"
      << "      <DataArray type=\"Int32\" Name=\"step\" NumberOfTuples=\"1\" format=\"ascii\">"
      << step << "</DataArray>\n"
      << "    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << body.num_nodes() << "\" NumberOfCells=\"" << cells.size()
      << "\">\n"
      << "      <Points>\n"
      << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (int n = 0; n < body.num_nodes(); ++n) {
    const Point x = body.reference(n);
    out << "         ";
    for (int c = 0; c < 3; ++c) out << ' ' << (c < dim ? x[c] : 0.0);
    out << '\n';
  }
  out << "        </DataArray>\n      </Points>\n      <Cells>\n";
  WriteConnectivity(out, cells);
  out << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n         ";
  for (const auto& cell : cells) out << ' ' << VtkCellType(cell.size(), dim);
  out << "\n        </DataArray>\n      </Cells>\n"
      << "      <PointData Vectors=\"displacement\" Scalars=\"contact_reaction\">\n"
      << "        <DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (int n = 0; n < body.num_nodes(); ++n) {
    const Point x = body.reference(n);
    const Point moved = body.Position(n, state.u);
    out << "         ";
    for (int c = 0; c < 3; ++c) out << ' ' << (c < dim ? moved[c] - x[c] : 0.0);
    out << '\n';
  }
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Float64\" Name=\"contact_reaction\" format=\"ascii\">\n";
  for (double r : reaction) out << "          " << r << '\n';
  out << "        </DataArray>\n      </PointData>\n";
  const std::vector<CellField> fields = body.CellFields(state.u);
  out << "      <CellData"
      << (fields.empty() ? "" : " Scalars=\"" + XmlEscaped(fields.front().name) + "\"") << ">\n";
  for (const CellField& field : fields) {
    out << "        <DataArray type=\"Float64\" Name=\"" << XmlEscaped(field.name)
        << "\" format=\"ascii\">\n         ";
    for (double v : field.values) out << ' ' << v;
    out << "\n        </DataArray>\n";
  }
  out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  CloseOrRemove(out, path);
}

void WriteSurfaceVtp(const std::string& path, const SurfaceGeometry& surface,
                     const std::string& id) {
  std::ofstream out = Open(path);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <PolyData>\n"
      << "    <FieldData>\n"
      << "      <Array type=\"String\" Name=\"id\" NumberOfTuples=\"1\" format=\"ascii\">";
  // VTK's ASCII strings are byte values, each string ended by a 0.
  for (unsigned char c : id) out << static_cast<int>(c) << ' ';
  out << "0</Array>\n"
      << "    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << surface.points.size() << "\" NumberOfVerts=\"0\" "
      << "NumberOfLines=\"" << surface.lines.size() << "\" NumberOfStrips=\"0\" "
      << "NumberOfPolys=\"" << surface.polygons.size() << "\">\n"
      << "      <Points>\n"
      << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Point3& p : surface.points) {
    out << "          " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  }
  out << "        </DataArray>\n      </Points>\n";
  if (!surface.lines.empty()) {
    out << "      <Lines>\n";
    WriteConnectivity(out, surface.lines);
    out << "      </Lines>\n";
  }
  if (!surface.polygons.empty()) {
    out << "      <Polys>\n";
    WriteConnectivity(out, surface.polygons);
    out << "      </Polys>\n";
  }
  out << "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  CloseOrRemove(out, path);
}

void WritePvd(const std::string& path, const std::vector<PvdDataSet>& datasets) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out = Open(temporary);
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
    CloseOrRemove(out, temporary);
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);  // atomic: never a half-written collection
  if (ec) throw WriteError(path, "cannot rename '" + temporary + "' to it: " + ec.message());
}

}  // namespace cb::harness
