#include "harness/records.h"

#include <unistd.h>

#include <cstdio>

#include "core/types.h"

namespace cb::harness {

RunRecorder::RunRecorder(const std::string& directory, const Problem& problem, RunLabel label)
    : directory_(directory), problem_(problem), label_(std::move(label)) {
  steps_ = std::make_unique<CsvWriter>(
      directory + "/steps.csv",
      std::vector<std::string>{
          "problem",       "formulation",  "solver",       "start",          "step",
          "lambda",        "control_disp", "iterations",   "residual_evals", "jacobian_evals",
          "linear_solves", "time_s",       "found",        "verified",       "eq_res",
          "comp_res",      "feas_res",     "step_res",     "n_contact",      "kink",
          "attempt",       "accepted",     "reversed",     "constraint",     "arc_length",
          "status",        "settings",     "length_scale", "force_scale",    "message"});
  iterations_ = std::make_unique<CsvWriter>(
      directory + "/iterations.csv",
      std::vector<std::string>{"problem", "formulation", "solver", "start", "step", "attempt",
                               "iteration", "merit", "residual_inf", "comp_res", "step_length"});
  kinks_ = std::make_unique<CsvWriter>(
      directory + "/kinks.csv",
      std::vector<std::string>{"problem", "formulation", "step", "pair", "lambda", "control_disp",
                               "verified", "between", "iterations", "eq_res", "comp_res",
                               "feas_res", "step_res", "time_s", "status", "message"});
  total_steps_ = problem.loading == LoadingKind::kFixedLoad ? 1 : problem.steps;
  progress_ = isatty(STDERR_FILENO) == 1;
}

double RunRecorder::ControlDisplacement(const State& state) const {
  return problem_.control_dof >= 0 ? state.u[problem_.control_dof] : 0.0;
}

void RunRecorder::OnAttempt(const StepAttempt& a) {
  ++attempts_;
  const StepResult& res = a.result;
  const bool found = res.status == Status::kConverged;
  if (!a.accepted) all_verified_ = false;
  CsvWriter::Row row;
  row << label_.problem << label_.formulation << label_.solver << label_.start << a.step
      << a.state.lambda << ControlDisplacement(a.state) << res.counts.iterations
      << res.counts.residual_evals << res.counts.jacobian_evals << res.counts.linear_solves
      << res.time_s << found << a.verdict.verified << a.verdict.eq_res << a.verdict.comp_res
      << a.verdict.feas_res << a.verdict.step_res << a.n_contact << a.kinks << a.attempt
      << a.accepted << a.reversed << ToString(a.kind) << a.arc_length << ToString(res.status)
      << label_.settings << problem_.scales.length << problem_.scales.force << res.message;
  steps_->Write(row);
  for (const IterationRecord& it : res.history) {
    CsvWriter::Row r;
    r << label_.problem << label_.formulation << label_.solver << label_.start << a.step
      << a.attempt << it.iteration << it.merit << it.residual_inf << it.comp_res << it.step_length;
    iterations_->Write(r);
  }
  if (progress_) {
    std::fprintf(stderr, "\r%s %s: step %d/%d%s lambda=%.6g iterations=%d   ",
                 label_.problem.c_str(), label_.formulation.c_str(), a.step, total_steps_,
                 a.accepted ? "" : " (retry)", a.state.lambda, res.counts.iterations);
    if (a.step == total_steps_ && a.accepted) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }
}

void RunRecorder::OnKink(const KinkRecord& k) {
  CsvWriter::Row row;
  row << label_.problem << label_.formulation << k.step << k.pair << k.state.lambda
      << ControlDisplacement(k.state) << k.verdict.verified << k.between
      << k.result.counts.iterations << k.verdict.eq_res << k.verdict.comp_res << k.verdict.feas_res
      << k.verdict.step_res << k.result.time_s << ToString(k.result.status) << k.result.message;
  kinks_->Write(row);
}

void RunRecorder::WriteSnapshot(const State& state, int step) const {
  if (!problem_.body) return;  // not a mechanical body: no nodes to write
  const BodyContactModel& model = *problem_.body;
  const ElasticBody& body = model.body();
  const int dim = body.dim();
  std::vector<std::string> columns = {"step", "node", "x", "y"};
  if (dim == 3) columns.push_back("z");
  columns.insert(columns.end(), {"ux", "uy"});
  if (dim == 3) columns.push_back("uz");
  CsvWriter solution(directory_ + "/solution.csv", columns);
  for (int n = 0; n < body.num_nodes(); ++n) {
    const Point x = body.reference(n);
    const Point moved = body.Position(n, state.u);
    CsvWriter::Row row;
    row << step << n;
    for (int c = 0; c < dim; ++c) row << x[c];
    for (int c = 0; c < dim; ++c) row << moved[c] - x[c];
    solution.Write(row);
  }
  Vec phi;
  model.Gaps(state.u, &phi);
  CsvWriter contacts(directory_ + "/contacts.csv",
                     {"step", "pair", "node", "obstacle", "g", "r", "lambda"});
  for (int p = 0; p < model.num_pairs(); ++p) {
    CsvWriter::Row row;
    row << step << p << model.pairs()[p].node << model.pairs()[p].obstacle << -phi[p] << state.r[p]
        << state.lambda;
    contacts.Write(row);
  }
}

}  // namespace cb::harness
