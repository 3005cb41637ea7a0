#include "harness/records.h"

#include <cstdio>
#include <limits>

#include "harness/interrupt.h"
#include "model/complementarity_model.h"
#include "verdict/natural_map_error.h"

namespace cb::harness {

RecordFiles::RecordFiles(const RecordTarget& target)
    : steps_(target, StepsSchema()),
      iterations_(target, IterationsSchema()),
      kinks_(target, KinksSchema()),
      critical_(target, CriticalSchema()) {}

RunRecorder::RunRecorder(RecordFiles* files, const Problem& problem, RunLabel label,
                         int total_steps)
    : files_(files), problem_(problem), label_(std::move(label)), total_steps_(total_steps) {
  // A fall-back to a direct LU costs minutes only where the fill is a 3-D mesh's (SlowWorkText).
  if (problem_.body && problem_.body->body().dim() == 3) progress_.ShowSlowWork();
}

double RunRecorder::StepFclibError(const State& state) const {
  const bool lcp = dynamic_cast<const ComplementarityModel*>(problem_.model.get()) != nullptr;
  if (!problem_.from_fclib && !lcp) return std::numeric_limits<double>::quiet_NaN();
  return NaturalMapError(*problem_.model, state);
}

void RunRecorder::OnAttempt(const StepAttempt& a) {
  ++attempts_;
  if (!a.accepted) all_verified_ = false;
  if (a.accepted) ++accepted_;
  iterations_.push_back(a.result.counts.iterations);
  solve_times_s_.push_back(a.result.time_s);
  // NaN-safe: the first attempt's spread replaces the NaN start (a comparison with NaN is false).
  if (!(fastest_solve_s_ <= a.result.time_min_s)) fastest_solve_s_ = a.result.time_min_s;
  if (!(slowest_solve_s_ >= a.result.time_max_s)) slowest_solve_s_ = a.result.time_max_s;
  if (!a.result.repeats_disagreement.empty()) {
    if (first_disagreement_.empty()) {
      first_disagreement_ = "step " + std::to_string(a.step) + ", " + a.result.repeats_disagreement;
    }
    ++repeat_disagreements_;
  }
  files_->steps().Write({label_, problem_, a, StepFclibError(a.state)});
  for (const IterationRecord& it : a.result.history) files_->iterations().Write({label_, a, it});
  ShowProgress(a);
}

void RunRecorder::ShowProgress(const StepAttempt& a) {
  char text[256];
  std::snprintf(text, sizeof text, "%s %s (%s): step %d/%d%s lambda=%.6g iterations=%d",
                label_.problem.c_str(), label_.formulation.c_str(), label_.start.c_str(), a.step,
                total_steps_, a.accepted ? "" : " (not verified)", a.state.lambda,
                a.result.counts.iterations);
  progress_.Update(text, accepted_, total_steps_);
}

void RunRecorder::OnKink(const KinkRecord& k) { files_->kinks().Write({label_, problem_, k}); }

void RunRecorder::OnCriticalPoint(const CriticalPointRecord& c) {
  files_->critical().Write({label_, problem_, c});
}

std::int64_t NodeId(const Problem& problem, int node) {
  return problem.node_ids.empty() ? node : problem.node_ids.at(static_cast<std::size_t>(node));
}

std::string ObstacleId(const Problem& problem, int obstacle) {
  return problem.obstacle_ids.empty() ? std::to_string(obstacle)
                                      : problem.obstacle_ids.at(static_cast<std::size_t>(obstacle));
}

std::vector<NodeRow> NodeRows(const Problem& problem, const State& state, int step,
                              std::string_view label) {
  const ElasticBody& body = problem.body->body();
  std::vector<NodeRow> rows;
  rows.reserve(body.num_nodes());
  for (int n = 0; n < body.num_nodes(); ++n) {
    rows.push_back({step, label, state.lambda, NodeId(problem, n), body.reference(n),
                    body.Position(n, state.u)});
  }
  return rows;
}

std::vector<PairRow> PairRows(const Problem& problem, const State& state, int step,
                              std::string_view label) {
  const BodyContactModel& model = *problem.body;
  Vec phi;
  model.Gaps(state.u, &phi);
  std::vector<PairRow> rows;
  rows.reserve(model.num_pairs());
  for (int p = 0; p < model.num_pairs(); ++p) {
    const ContactPair& pair = model.pairs()[p];
    rows.push_back({step, label, state.lambda, p, NodeId(problem, pair.node),
                    ObstacleId(problem, pair.obstacle), -phi[p], state.r[p]});
  }
  return rows;
}

namespace {

void WriteBodyState(const RecordTarget& target, const Problem& problem, const State& state,
                    int step) {
  RecordWriter<NodeRow> solution(target, SolutionSchema(), problem.body->body().dim());
  for (const NodeRow& row : NodeRows(problem, state, step, "final")) {
    StopIfInterrupted("writing solution.csv");
    solution.Write(row);
  }
  RecordWriter<PairRow> contacts(target, ContactsSchema());
  for (const PairRow& row : PairRows(problem, state, step, "final")) {
    StopIfInterrupted("writing contacts.csv");
    contacts.Write(row);
  }
}

void WriteComplementarityState(const RecordTarget& target, const ComplementarityModel& model,
                               const State& state, int step) {
  Vec w;
  model.InternalForce(state.u, &w);  // M z + q
  RecordWriter<ComplementarityRow> solution(target, ComplementaritySolutionSchema());
  for (int i = 0; i < model.num_dofs(); ++i) {
    StopIfInterrupted("writing solution.csv");
    solution.Write({step, i, state.u[i], w[i]});
  }
}

}  // namespace

void WriteFinalState(const RecordTarget& target, const Problem& problem, const State& state,
                     int step) {
  if (problem.body != nullptr) {
    WriteBodyState(target, problem, state, step);
  } else if (const auto* lcp = dynamic_cast<const ComplementarityModel*>(problem.model.get())) {
    WriteComplementarityState(target, *lcp, state, step);
  }
}

void WriteParameters(const RecordTarget& target, const Problem& problem) {
  RecordWriter<ParameterRow> parameters(target, ParametersSchema());
  for (const auto& e : problem.parameters.entries()) {
    parameters.Write({problem.name, e.name, e.value, e.doc});
  }
  const std::string dofs = std::to_string(problem.model->num_dofs());
  const std::string pairs = std::to_string(problem.model->num_pairs());
  parameters.Write({problem.name, "num_dofs", dofs, "d, displacement unknowns (model size)"});
  parameters.Write({problem.name, "num_pairs", pairs, "nc, contact pairs (model size)"});
}

}  // namespace cb::harness
