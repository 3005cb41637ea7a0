#include "harness/snapshots.h"

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <map>

#include "formulations/petsc_dist/petsc_dist.h"
#include "harness/interrupt.h"
#include "harness/process_agreement.h"
#include "harness/records.h"
#include "harness/vtk_files.h"
#include "harness/vtk_pieces.h"

namespace cb::harness {

SnapshotWriter::SnapshotWriter(const std::string& directory, const Problem& problem, int every)
    : directory_(directory),
      problem_(problem),
      every_(every),
      process_(DistributedRank()),
      processes_(DistributedSize()) {
  if (!problem_.body || process_ != 0) return;
  nodes_ = std::make_unique<RecordWriter<NodeRow>>(directory, SnapshotsSchema(),
                                                   problem_.body->body().dim());
  contacts_ = std::make_unique<RecordWriter<PairRow>>(directory, SnapshotContactsSchema());
  std::filesystem::create_directories(directory + "/vtk");
  // The elements, so that plots can draw the deformed mesh from the CSV files alone.
  RecordWriter<CellCornerRow> cells(directory, CellsSchema());
  const std::vector<std::vector<int>> all = problem_.body->body().Cells();
  for (std::size_t c = 0; c < all.size(); ++c) {
    StopIfInterrupted("writing cells.csv");
    for (std::size_t k = 0; k < all[c].size(); ++k) {
      cells.Write({static_cast<int>(c), static_cast<int>(k), NodeId(problem_, all[c][k])});
    }
  }
  WriteObstacles();
}

// Each obstacle's surface around the body's reference configuration, written once: obstacles
// are rigid and fixed.
void SnapshotWriter::WriteObstacles() {
  const ElasticBody& body = problem_.body->body();
  std::vector<Point> reference;
  reference.reserve(body.num_nodes());
  for (int n = 0; n < body.num_nodes(); ++n) reference.push_back(body.reference(n));
  const Box around = BoxAround(reference);
  const auto& obstacles = problem_.body->obstacles();
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const std::string file = problem_.name + "_obstacle_" + std::to_string(k) + ".vtp";
    const std::string id = ObstacleId(problem_, static_cast<int>(k));
    WriteSurfaceVtp(directory_ + "/vtk/" + file, ObstacleSurface(*obstacles[k], around), id);
    obstacles_.push_back({file, id});
  }
}

void SnapshotWriter::OnAttempt(const StepAttempt& a) {
  if (a.accepted && every_ > 0 && a.step % every_ == 0) Save(a.state, a.step, "step");
}

void SnapshotWriter::OnCriticalPoint(const CriticalPointRecord& c) {
  if (c.kind == CriticalPointRecord::Kind::kStabilityChange) return;
  SaveAt(c.state, c.step, ToString(c.kind), c.step - 0.5);  // between steps step - 1 and step
}

void SnapshotWriter::SaveAt(const State& state, int step, const std::string& label, double time) {
  if (!problem_.body) return;
  char number[32];
  std::snprintf(number, sizeof number, "_%04d", static_cast<int>(saved_.size()));
  const std::string stem = problem_.name + number;
  std::string file;
  if (processes_ == 1) {
    WriteRows(state, step, label);
    file = WriteBody(stem, state, step);
  } else {
    OnEveryProcess("saving state " + stem, [&] {
      if (process_ == 0) WriteRows(state, step, label);
      file = WritePieces(stem, state, step);
    });
  }
  saved_.push_back({file, step, label, state.lambda, time});
  if (processes_ == 1) {
    WriteCollection();
  } else {  // the index and the collection once every piece is whole
    OnEveryProcess("indexing state " + stem, [&] {
      if (process_ != 0) return;
      WriteIndex(stem, state);
      WriteCollection();
    });
  }
}

void SnapshotWriter::WriteIndex(const std::string& stem, const State& state) const {
  std::vector<std::string> cell_fields;  // the names, which an element-less body has too
  for (const CellField& f : problem_.body->body().Restricted({})->CellFields(state.u)) {
    cell_fields.push_back(f.name);
  }
  std::vector<std::string> pieces;
  pieces.reserve(static_cast<std::size_t>(processes_));
  for (int p = 0; p < processes_; ++p) pieces.push_back(PieceFile(stem, p));
  WriteBodyPvtu(directory_ + "/vtk/" + stem + ".pvtu", cell_fields, pieces);
}

void SnapshotWriter::WriteRows(const State& state, int step, const std::string& label) {
  for (const NodeRow& row : NodeRows(problem_, state, step, label)) {
    StopIfInterrupted("writing snapshots.csv");
    nodes_->Write(row);
  }
  for (const PairRow& row : PairRows(problem_, state, step, label)) {
    StopIfInterrupted("writing snapshot_contacts.csv");
    contacts_->Write(row);
  }
}

std::string SnapshotWriter::WriteBody(const std::string& stem, const State& state, int step) {
  StopIfInterrupted("saving a state");
  std::string file = stem + ".vtu";
  WriteBodyVtu(directory_ + "/vtk/" + file, problem_, state, step);
  return file;
}

std::string SnapshotWriter::WritePieces(const std::string& stem, const State& state, int step) {
  StopIfInterrupted("saving a state");
  const ElasticBody& body = problem_.body->body();
  const BodyPiece piece = PieceOfProcess(body, ElementsOfEachProcess(body), process_, processes_);
  WriteBodyPieceVtu(directory_ + "/vtk/" + PieceFile(stem, process_), problem_, state, step, piece);
  return stem + ".pvtu";
}

void SnapshotWriter::WriteCollection() const {
  std::map<double, const Saved*> at_time;  // a later save at a time replaces an earlier one
  for (const Saved& saved : saved_) at_time[saved.time] = &saved;
  std::vector<PvdDataSet> datasets;
  for (const auto& [time, saved] : at_time) {
    char lambda[32];
    std::snprintf(lambda, sizeof lambda, "%.17g", saved->lambda);
    datasets.push_back(
        {time, 0, problem_.name, saved->file,
         "step " + std::to_string(saved->step) + ", " + saved->label + ", lambda " + lambda});
    for (std::size_t k = 0; k < obstacles_.size(); ++k) {
      datasets.push_back(
          {time, static_cast<int>(k) + 1, "obstacle " + obstacles_[k].id, obstacles_[k].file, ""});
    }
  }
  WritePvd(directory_ + "/vtk/" + problem_.name + ".pvd", datasets);
}

}  // namespace cb::harness
