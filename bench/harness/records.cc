#include "harness/records.h"

#include <unistd.h>

#include <cstdio>

#include "core/types.h"

namespace cb::harness {

RecordFiles::RecordFiles(const std::string& directory) : directory_(directory) {
  steps_ = std::make_unique<CsvWriter>(
      directory + "/steps.csv",
      std::vector<std::string>{"problem",        "formulation",    "solver",        "start",
                               "step",           "lambda",         "control_disp",  "iterations",
                               "residual_evals", "jacobian_evals", "linear_solves", "time_s",
                               "found",          "verified",       "eq_res",        "comp_res",
                               "feas_res",       "step_res",       "n_contact",     "kink",
                               "attempt",        "accepted",       "reversed",      "constraint",
                               "arc_length",     "status",         "settings",      "length_scale",
                               "force_scale",    "mode",           "unstable_modes", "branch",
                               "branch_switch",  "message"});
  iterations_ = std::make_unique<CsvWriter>(
      directory + "/iterations.csv",
      std::vector<std::string>{"problem", "formulation", "solver", "start", "step", "attempt",
                               "iteration", "merit", "residual_inf", "comp_res", "step_length",
                               "mode"});
  kinks_ = std::make_unique<CsvWriter>(
      directory + "/kinks.csv",
      std::vector<std::string>{"problem", "formulation", "start", "step", "pair", "lambda",
                               "control_disp", "verified", "between", "iterations", "eq_res",
                               "comp_res", "feas_res", "step_res", "time_s", "status", "message"});
  critical_ = std::make_unique<CsvWriter>(
      directory + "/critical.csv",
      std::vector<std::string>{"problem", "formulation", "start", "step", "kind", "nonsmooth",
                               "lambda", "control_disp", "located", "bisections", "verified",
                               "eq_res", "comp_res", "switched", "message"});
}

RunRecorder::RunRecorder(RecordFiles* files, const Problem& problem, RunLabel label,
                         int total_steps)
    : files_(files), problem_(problem), label_(std::move(label)), total_steps_(total_steps) {
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
  if (a.accepted) ++accepted_;
  CsvWriter::Row row;
  row << label_.problem << label_.formulation << label_.solver << label_.start << a.step
      << a.state.lambda << ControlDisplacement(a.state) << res.counts.iterations
      << res.counts.residual_evals << res.counts.jacobian_evals << res.counts.linear_solves
      << res.time_s << found << a.verdict.verified << a.verdict.eq_res << a.verdict.comp_res
      << a.verdict.feas_res << a.verdict.step_res << a.n_contact << a.kinks << a.attempt
      << a.accepted << a.reversed << ToString(a.kind) << a.arc_length << ToString(res.status)
      << label_.settings << problem_.scales.length << problem_.scales.force << label_.mode
      << a.stability << a.branch << a.branch_switch << res.message;
  files_->steps().Write(row);
  for (const IterationRecord& it : res.history) {
    CsvWriter::Row r;
    r << label_.problem << label_.formulation << label_.solver << label_.start << a.step
      << a.attempt << it.iteration << it.merit << it.residual_inf << it.comp_res << it.step_length
      << label_.mode;
    files_->iterations().Write(r);
  }
  if (progress_) {
    std::fprintf(stderr, "\r%s %s (%s): step %d/%d%s lambda=%.6g iterations=%d   ",
                 label_.problem.c_str(), label_.formulation.c_str(), label_.start.c_str(), a.step,
                 total_steps_, a.accepted ? "" : " (not verified)", a.state.lambda,
                 res.counts.iterations);
    if (a.step == total_steps_ && (a.accepted || label_.mode != "run")) {
      std::fprintf(stderr, "\n");
    }
    std::fflush(stderr);
  }
}

void RunRecorder::OnKink(const KinkRecord& k) {
  CsvWriter::Row row;
  row << label_.problem << label_.formulation << label_.start << k.step << k.pair << k.state.lambda
      << ControlDisplacement(k.state) << k.verdict.verified << k.between
      << k.result.counts.iterations << k.verdict.eq_res << k.verdict.comp_res << k.verdict.feas_res
      << k.verdict.step_res << k.result.time_s << ToString(k.result.status) << k.result.message;
  files_->kinks().Write(row);
}

void RunRecorder::OnCriticalPoint(const CriticalPointRecord& c) {
  CsvWriter::Row row;
  row << label_.problem << label_.formulation << label_.start << c.step << ToString(c.kind)
      << c.nonsmooth << c.state.lambda << ControlDisplacement(c.state) << c.located
      << c.bisections << c.verdict.verified << c.verdict.eq_res << c.verdict.comp_res
      << c.switched << c.message;
  files_->critical().Write(row);
}

void WriteSnapshot(const std::string& directory, const Problem& problem, const State& state,
                   int step) {
  if (!problem.body) return;  // not a mechanical body: no nodes to write
  const BodyContactModel& model = *problem.body;
  const ElasticBody& body = model.body();
  const int dim = body.dim();
  std::vector<std::string> columns = {"step", "node", "x", "y"};
  if (dim == 3) columns.push_back("z");
  columns.insert(columns.end(), {"ux", "uy"});
  if (dim == 3) columns.push_back("uz");
  CsvWriter solution(directory + "/solution.csv", columns);
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
  CsvWriter contacts(directory + "/contacts.csv",
                     {"step", "pair", "node", "obstacle", "g", "r", "lambda"});
  for (int p = 0; p < model.num_pairs(); ++p) {
    CsvWriter::Row row;
    row << step << p << model.pairs()[p].node << model.pairs()[p].obstacle << -phi[p] << state.r[p]
        << state.lambda;
    contacts.Write(row);
  }
}

}  // namespace cb::harness
