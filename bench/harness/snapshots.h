// Deformed configurations saved along a path: every N-th accepted step, every critical point
// (limit and bifurcation points) and the final state, as long-format CSV (DIR/snapshots.csv,
// one row per node and saved state; DIR/snapshot_contacts.csv, one row per pair and saved
// state) and as VTK files that open in ParaView (vtk_files.h): DIR/vtk/<problem>_NNNN.vtu, one
// per saved state, with the elements' quantities as cell data; DIR/vtk/<problem>_reference.vtu,
// the unloaded reference configuration; DIR/vtk/<problem>_obstacles.vtp, every obstacle in one
// poly data set (obstacle_patches.h, the cell array `obstacle`); and DIR/vtk/<problem>.pvd, the
// collection, rewritten after each save so that an interrupted run leaves a valid one. The
// collection's time is the arc length traced to a state (lambda on a fixed-load path): the
// reference at 0, a state saved after step k at the arc length of steps 1..k, a critical point
// found within step k half way along that step (a later save at the same time replaces an
// earlier one in it, as the final state replaces the regular save of the last step); each .vtu
// holds its step and lambda as field data; the obstacles are block 1 at every time. DIR/cells.csv
// lists the elements (cell, corner, node). The CSV columns are those of record_schemas.h.
//
// In a distributed run of several processes (formulations/petsc_dist/petsc_dist.h) every process
// keeps a writer and saves the same states: each writes its piece of the body,
// DIR/vtk/<problem>_NNNN_pP.vtu (vtk_pieces.h), and process 0 alone everything else, with
// DIR/vtk/<problem>_NNNN.pvtu, the parallel index of the pieces, in place of the .vtu (the
// collection lists the .pvtu). Process 0 makes DIR/vtk before the others write
// (process_agreement.h); a save that fails on any process fails on all of them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/record_schemas.h"
#include "parallel/element_split.h"
#include "path/path.h"
#include "problems/problem.h"

namespace cb::harness {

class SnapshotWriter final : public PathObserver {
 public:
  // `every`: save every this many accepted steps (0: only critical points and the final state).
  // Writes nothing for a problem that is not a body against obstacles (an LCP). Process 0 makes
  // DIR/vtk and writes the files of one process; the others only their pieces.
  // `split`: the run's split of the body's elements over the processes, which the formulation
  // records (none, or nothing recorded: process 0 holds the whole body).
  SnapshotWriter(const std::string& directory, const Problem& problem, int every,
                 const ElementSplit* split = nullptr);

  void OnAttempt(const StepAttempt& attempt) override;
  void OnCriticalPoint(const CriticalPointRecord& c) override;

  // Saves `state`, reached at step `step`, with a label ("step", "final", ...).
  void Save(const State& state, int step, const std::string& label) {
    SaveAt(state, step, label, CollectionTime(state, 0.0));
  }

  int saved() const { return static_cast<int>(saved_.size()); }

 private:
  struct Saved {
    std::string file;  // relative to DIR/vtk
    int step;
    std::string label;
    double lambda;
    double time;  // in the collection
  };
  // The time of a state in the collection: the arc length traced to it (`back` less), or, on
  // a fixed-load path (no arc), its lambda.
  double CollectionTime(const State& state, double back) const;
  void SaveAt(const State& state, int step, const std::string& label, double time);
  void WriteRows(const State& state, int step, const std::string& label);
  // The body at `state` as file `stem`.vtu, or in pieces with `stem`.pvtu; returns its file.
  std::string WriteBody(const std::string& stem, const State& state, int step);
  std::string WritePieces(const std::string& stem, const State& state, int step);
  void WriteIndex(const std::string& stem, const State& state) const;
  void WriteObstacles();
  void WriteReference();
  void WriteCollection() const;

  std::string directory_;
  const Problem& problem_;
  int every_ = 0;
  const ElementSplit* split_ = nullptr;
  int process_ = 0, processes_ = 1;
  std::unique_ptr<RecordWriter<NodeRow>> nodes_;
  std::unique_ptr<RecordWriter<PairRow>> contacts_;
  std::vector<Saved> saved_;
  std::string obstacles_file_;  // relative to DIR/vtk; empty: no obstacle
  std::string reference_file_;  // likewise; empty: not yet written
  double arc_length_ = 0.0;     // of the accepted steps so far
  double last_theta_ = 0.0;     // of the last accepted step
};

// Forwards every observation to several observers, in order.
class ObserverTee final : public PathObserver {
 public:
  explicit ObserverTee(std::vector<PathObserver*> observers) : observers_(std::move(observers)) {}
  void OnAttempt(const StepAttempt& a) override {
    for (PathObserver* o : observers_) o->OnAttempt(a);
  }
  void OnKink(const KinkRecord& k) override {
    for (PathObserver* o : observers_) o->OnKink(k);
  }
  void OnCriticalPoint(const CriticalPointRecord& c) override {
    for (PathObserver* o : observers_) o->OnCriticalPoint(c);
  }

 private:
  std::vector<PathObserver*> observers_;
};

}  // namespace cb::harness
