// Deformed configurations saved along a path: every N-th accepted step, every critical point
// (limit and bifurcation points) and the final state, as long-format CSV (DIR/snapshots.csv,
// one row per node and saved state; DIR/snapshot_contacts.csv, one row per pair and saved
// state) and as VTK files that open in ParaView (DIR/vtk/<problem>_NNNN.vtu, one per saved
// state, collected by DIR/vtk/<problem>.pvd, rewritten after each save so that an interrupted
// run leaves a valid collection). DIR/cells.csv lists the elements (cell, corner, node). The
// CSV columns are those of record_schemas.h.
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
  // Writes nothing for a problem that is not a body against obstacles (an LCP).
  SnapshotWriter(const std::string& directory, const Problem& problem, int every);

  void OnAttempt(const StepAttempt& attempt) override;
  void OnCriticalPoint(const CriticalPointRecord& c) override;

  // Saves `state` with a label ("step", "limit", "bifurcation", "final", ...).
  void Save(const State& state, int step, const std::string& label);

  int saved() const { return static_cast<int>(saved_.size()); }

 private:
  struct Saved {
    std::string file;  // relative to DIR/vtk
    int step;
    std::string label;
    double lambda;
  };
  void WriteVtu(const std::string& path, const State& state, int step) const;
  void WritePvd() const;

  std::string directory_;
  const Problem& problem_;
  int every_ = 0;
  std::unique_ptr<RecordWriter<NodeRow>> nodes_;
  std::unique_ptr<RecordWriter<PairRow>> contacts_;
  std::vector<Saved> saved_;
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
