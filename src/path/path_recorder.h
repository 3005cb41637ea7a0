// The accepted steps of a path, recorded by observing TraceArcLengthPath (or SolveFixedLoad):
// the reference path a replay gives every formulation (replay.h).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "path/path.h"

namespace cb {

// One accepted step.
struct RecordedStep {
  State state;              // the state after the step
  StepPoint increment;      // (du, r, dlambda) of the step
  StepPoint prediction;     // the predicted increment (du, dlambda) its warm start was given
  double arc_length = 0.0;  // theta it was taken with (arc-length steps)
  ConstraintKind kind = ConstraintKind::kArcLength;
};

class PathRecorder final : public PathObserver {
 public:
  // A read-only view of one field of every recorded step: column[k] is steps[k].*Field.
  template <auto Field>
  class Column {
   public:
    explicit Column(const std::vector<RecordedStep>& steps) : steps_(&steps) {}
    std::size_t size() const { return steps_->size(); }
    bool empty() const { return steps_->empty(); }
    const auto& operator[](std::size_t k) const { return (*steps_)[k].*Field; }
    const auto& back() const { return steps_->back().*Field; }

   private:
    const std::vector<RecordedStep>* steps_;
  };

  PathRecorder() = default;
  // The columns view the recorder's own steps, not those of the one copied or moved from.
  PathRecorder(const PathRecorder& other) : steps(other.steps), kinks(other.kinks) {}
  PathRecorder(PathRecorder&& other) noexcept
      : steps(std::move(other.steps)), kinks(std::move(other.kinks)) {}
  PathRecorder& operator=(const PathRecorder& other) {
    steps = other.steps;
    kinks = other.kinks;
    return *this;
  }
  PathRecorder& operator=(PathRecorder&& other) noexcept {
    steps = std::move(other.steps);
    kinks = std::move(other.kinks);
    return *this;
  }

  void OnAttempt(const StepAttempt& attempt) override;
  void OnKink(const KinkRecord& kink) override { kinks.push_back(kink); }

  // steps[k] is accepted step k + 1.
  std::vector<RecordedStep> steps;
  std::vector<KinkRecord> kinks;

  // The steps' fields by column, for readers that index them so.
  Column<&RecordedStep::state> states{steps};
  Column<&RecordedStep::increment> increments{steps};
  Column<&RecordedStep::prediction> predictions{steps};
  Column<&RecordedStep::arc_length> arc_lengths{steps};
  Column<&RecordedStep::kind> kinds{steps};
};

}  // namespace cb
