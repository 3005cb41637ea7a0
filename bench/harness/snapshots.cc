#include "harness/snapshots.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "harness/records.h"

namespace cb::harness {

namespace {

// VTK cell types of the legacy/XML formats.
constexpr int kVtkLine = 3;
constexpr int kVtkQuad = 9;
constexpr int kVtkHexahedron = 12;

int VtkCellType(std::size_t nodes) {
  return nodes == 2 ? kVtkLine : nodes == 8 ? kVtkHexahedron : kVtkQuad;
}

// Text in an XML attribute or comment.
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

// Closes `out` (which flushes it) and checks every write: a VTK file cut short is no VTK file,
// so it is removed rather than kept.
void CloseOrRemove(std::ofstream& out, const std::string& path) {
  out.close();
  if (out) return;
  std::error_code ec;
  std::filesystem::remove(path, ec);
  throw WriteError(path, "the write failed (disk full?); the file was removed");
}

// The body's per-cell quantities (a hexahedral solid's von Mises stress), one value per cell.
void WriteCellFields(std::ofstream& out, const std::vector<CellField>& fields) {
  if (fields.empty()) return;
  out << "      <CellData>\n";
  for (const CellField& field : fields) {
    out << "        <DataArray type=\"Float64\" Name=\"" << XmlEscaped(field.name)
        << "\" format=\"ascii\">\n";
    for (double v : field.values) out << "          " << v << '\n';
    out << "        </DataArray>\n";
  }
  out << "      </CellData>\n";
}

}  // namespace

SnapshotWriter::SnapshotWriter(const std::string& directory, const Problem& problem, int every)
    : directory_(directory), problem_(problem), every_(every) {
  if (!problem_.body) return;
  nodes_ = std::make_unique<RecordWriter<NodeRow>>(directory, SnapshotsSchema(),
                                                   problem_.body->body().dim());
  contacts_ = std::make_unique<RecordWriter<PairRow>>(directory, SnapshotContactsSchema());
  std::filesystem::create_directories(directory + "/vtk");
  // The elements, so that plots can draw the deformed mesh from the CSV files alone.
  RecordWriter<CellCornerRow> cells(directory, CellsSchema());
  const std::vector<std::vector<int>> all = problem_.body->body().Cells();
  for (std::size_t c = 0; c < all.size(); ++c) {
    for (std::size_t k = 0; k < all[c].size(); ++k) {
      cells.Write({static_cast<int>(c), static_cast<int>(k), all[c][k]});
    }
  }
}

void SnapshotWriter::OnAttempt(const StepAttempt& a) {
  if (a.accepted && every_ > 0 && a.step % every_ == 0) Save(a.state, a.step, "step");
}

void SnapshotWriter::OnCriticalPoint(const CriticalPointRecord& c) {
  if (c.kind == CriticalPointRecord::Kind::kStabilityChange) return;
  Save(c.state, c.step, ToString(c.kind));
}

void SnapshotWriter::Save(const State& state, int step, const std::string& label) {
  if (!problem_.body) return;
  for (const NodeRow& row : NodeRows(*problem_.body, state, step, label)) nodes_->Write(row);
  for (const PairRow& row : PairRows(*problem_.body, state, step, label)) contacts_->Write(row);
  char name[64];
  std::snprintf(name, sizeof name, "_%04d.vtu", static_cast<int>(saved_.size()));
  const std::string file = problem_.name + name;
  WriteVtu(directory_ + "/vtk/" + file, state, step);
  saved_.push_back({file, step, label, state.lambda});
  WritePvd();
}

// VTK XML unstructured grid (ASCII): reference points, the elements as cells, and as point
// data the displacement (3 components, so ParaView's "Warp By Vector" applies) and the sum of
// the contact reactions at each node; as cell data what the body provides per cell; the load
// parameter and step as field data.
void SnapshotWriter::WriteVtu(const std::string& path, const State& state, int step) const {
  const BodyContactModel& model = *problem_.body;
  const ElasticBody& body = model.body();
  const int dim = body.dim();
  const std::vector<std::vector<int>> cells = body.Cells();
  std::vector<double> reaction(body.num_nodes(), 0.0);
  for (int p = 0; p < model.num_pairs(); ++p) reaction[model.pairs()[p].node] += state.r[p];

  std::ofstream out(path);
  if (!out) throw WriteError(path, "cannot open it");
  out.precision(17);
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
  out << "        </DataArray>\n      </Points>\n      <Cells>\n"
      << "        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n         ";
  for (const auto& cell : cells) {
    for (int n : cell) out << ' ' << n;
  }
  out << "\n        </DataArray>\n"
      << "        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n         ";
  int offset = 0;
  for (const auto& cell : cells) out << ' ' << (offset += static_cast<int>(cell.size()));
  out << "\n        </DataArray>\n"
      << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n         ";
  for (const auto& cell : cells) out << ' ' << VtkCellType(cell.size());
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
  WriteCellFields(out, body.CellFields(state.u));
  out << "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  CloseOrRemove(out, path);
}

// The collection, one dataset per saved state in order; the "timestep" is the save index
// (two saves may share a step: a critical point and the regular save).
void SnapshotWriter::WritePvd() const {
  const std::string path = directory_ + "/vtk/" + problem_.name + ".pvd";
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary);
    if (!out) throw WriteError(temporary, "cannot open it");
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (std::size_t k = 0; k < saved_.size(); ++k) {
      out << "    <DataSet timestep=\"" << k << "\" group=\"\" part=\"0\" file=\""
          << XmlEscaped(saved_[k].file) << "\"/>  <!-- step " << saved_[k].step << ", "
          << saved_[k].label << ", lambda " << saved_[k].lambda << " -->\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
    CloseOrRemove(out, temporary);
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);  // atomic: never a half-written collection
  if (ec) throw WriteError(path, "cannot rename '" + temporary + "' to it: " + ec.message());
}

}  // namespace cb::harness
