#include "harness/snapshots.h"

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <map>

#include "harness/interrupt.h"
#include "harness/obstacle_patches.h"
#include "harness/process_agreement.h"
#include "harness/records.h"
#include "harness/vtk_files.h"
#include "harness/vtk_pieces.h"
#include "parallel/processes.h"

namespace cb::harness {

SnapshotWriter::SnapshotWriter(const std::string& directory, const Problem& problem, int every,
                               const ElementSplit* split)
    : directory_(directory),
      problem_(problem),
      every_(every),
      split_(split),
      process_(ProcessRank()),
      processes_(ProcessCount()) {
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

// The obstacles, written once in one file: obstacles are rigid and fixed.
void SnapshotWriter::WriteObstacles() {
  const auto& obstacles = problem_.body->obstacles();
  if (!obstacles.empty()) {
    std::vector<std::string> ids;
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      ids.push_back(ObstacleId(problem_, static_cast<int>(k)));
    }
    obstacles_file_ = problem_.name + "_obstacles.vtp";
    WriteObstaclesVtp(directory_ + "/vtk/" + obstacles_file_, DrawnObstacles(*problem_.body), ids);
  }
}

// The unloaded reference configuration (u = 0, lambda = 0, step 0), the first time of the
// collection, as the saved states are written (in pieces with their index in a distributed run).
void SnapshotWriter::WriteReference() {
  const State zero = ZeroState(*problem_.model);
  const std::string stem = problem_.name + "_reference";
  if (processes_ == 1) {
    reference_file_ = WriteBody(stem, zero, 0);
    return;
  }
  std::string file;
  OnEveryProcess("saving the reference state", [&] { file = WritePieces(stem, zero, 0); });
  OnEveryProcess("indexing the reference state", [&] {  // once every piece is whole
    if (process_ == 0) WriteIndex(stem, zero);
  });
  reference_file_ = file;
}

void SnapshotWriter::OnAttempt(const StepAttempt& a) {
  if (a.accepted) {
    arc_length_ += a.arc_length;
    last_theta_ = a.arc_length;
  }
  if (a.accepted && every_ > 0 && a.step % every_ == 0) Save(a.state, a.step, "step");
}

void SnapshotWriter::OnCriticalPoint(const CriticalPointRecord& c) {
  if (c.kind == CriticalPointRecord::Kind::kStabilityChange) return;
  // Between steps step - 1 and step: half way along the step's arc.
  SaveAt(c.state, c.step, ToString(c.kind), CollectionTime(c.state, 0.5 * last_theta_));
}

double SnapshotWriter::CollectionTime(const State& state, double back) const {
  return arc_length_ > 0.0 ? arc_length_ - back : state.lambda;
}

void SnapshotWriter::SaveAt(const State& state, int step, const std::string& label, double time) {
  if (!problem_.body) return;
  if (reference_file_.empty()) WriteReference();
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
  // The names and components, which an element-less body has too.
  const std::vector<CellField> cell_fields =
      problem_.body->body().Restricted({})->CellFields(state.u);
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
  const std::vector<std::vector<int>> parts =
      split_ != nullptr ? split_->ElementsOfEachProcess(body.Cells().size())
                        : std::vector<std::vector<int>>();
  const BodyPiece piece = PieceOfProcess(body, parts, process_, processes_);
  WriteBodyPieceVtu(directory_ + "/vtk/" + PieceFile(stem, process_), problem_, state, step, piece);
  return stem + ".pvtu";
}

void SnapshotWriter::WriteCollection() const {
  std::map<double, const Saved*> at_time;  // a later save at a time replaces an earlier one
  for (const Saved& saved : saved_) at_time[saved.time] = &saved;
  std::vector<PvdDataSet> datasets;
  const auto add = [&](double time, const std::string& file, const std::string& comment) {
    datasets.push_back({time, 0, problem_.name, file, comment});
    if (!obstacles_file_.empty()) {
      datasets.push_back({time, 1, "obstacles", obstacles_file_, ""});
    }
  };
  if (!reference_file_.empty() && !at_time.contains(0.0)) {
    add(0.0, reference_file_, "the reference configuration, lambda 0");
  }
  for (const auto& [time, saved] : at_time) {
    char lambda[32];
    std::snprintf(lambda, sizeof lambda, "%.17g", saved->lambda);
    add(time, saved->file,
        "step " + std::to_string(saved->step) + ", " + saved->label + ", lambda " + lambda);
  }
  WritePvd(directory_ + "/vtk/" + problem_.name + ".pvd", datasets);
}

}  // namespace cb::harness
