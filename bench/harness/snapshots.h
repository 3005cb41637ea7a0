// Deformed configurations saved along a path: every N-th accepted step, every critical point
// (limit and bifurcation points) and the final state, as long-format CSV (DIR/snapshots.csv,
// one row per node and saved state; DIR/snapshot_contacts.csv, one row per pair and saved
// state) and as VTK files that open in ParaView (vtk_files.h): DIR/vtk/<problem>_NNNN.vtu, one
// per saved state, with the elements' quantities as cell data; DIR/vtk/<problem>_obstacle_K.vtp,
// one per obstacle; and DIR/vtk/<problem>.pvd, the collection, rewritten after each save so
// that an interrupted run leaves a valid one. The collection's time is the step: a state saved
// at step k is at time k, a critical point found between steps k - 1 and k at k - 1/2 (a later
// save at the same time replaces an earlier one in it, as the final state replaces the regular
// save of the last step); the obstacles are blocks of their own at every time. DIR/cells.csv
// lists the elements (cell, corner, node). The CSV columns are those of record_schemas.h.
//
// In a distributed run of several processes (petsc_dist.h) every process keeps a writer and
// saves the same states: each writes its piece of the body, DIR/vtk/<problem>_NNNN_pP.vtu
// (vtk_pieces.h), and process 0 alone everything else, with DIR/vtk/<problem>_NNNN.pvtu, the
// parallel index of the pieces, in place of the .vtu (the collection lists the .pvtu). Process 0
// makes DIR/vtk before the others write (process_agreement.h); a save that fails on any process
// fails on all of them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/record_schemas.h"
#include "path/path.h"
#include "problems/problem.h"

namespace cb::harness {

class SnapshotWriter final : public PathObserver {
 public:
  // `every`: save every this many accepted steps (0: only critical points and the final state).
  // Writes nothing for a problem that is not a body against obstacles (an LCP). Process 0 makes
  // DIR/vtk and writes the files of one process; the others only their pieces.
  SnapshotWriter(const std::string& directory, const Problem& problem, int every);

  void OnAttempt(const StepAttempt& attempt) override;
  void OnCriticalPoint(const CriticalPointRecord& c) override;

  // Saves `state`, reached at step `step`, with a label ("step", "final", ...).
  void Save(const State& state, int step, const std::string& label) {
    SaveAt(state, step, label, step);
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
  struct ObstacleFile {
    std::string file;  // relative to DIR/vtk
    std::string id;
  };
  void SaveAt(const State& state, int step, const std::string& label, double time);
  void WriteRows(const State& state, int step, const std::string& label);
  // The body at `state` as file `stem`.vtu, or in pieces with `stem`.pvtu; returns its file.
  std::string WriteBody(const std::string& stem, const State& state, int step);
  std::string WritePieces(const std::string& stem, const State& state, int step);
  void WriteIndex(const std::string& stem, const State& state) const;
  void WriteObstacles();
  void WriteCollection() const;

  std::string directory_;
  const Problem& problem_;
  int every_ = 0;
  int process_ = 0, processes_ = 1;
  std::unique_ptr<RecordWriter<NodeRow>> nodes_;
  std::unique_ptr<RecordWriter<PairRow>> contacts_;
  std::vector<Saved> saved_;
  std::vector<ObstacleFile> obstacles_;
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
