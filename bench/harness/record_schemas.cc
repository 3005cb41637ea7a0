#include "harness/record_schemas.h"

#include <limits>

namespace cb::harness {

namespace {

// The problem's control displacement at `state` (0 when the problem names none).
double ControlDisplacement(const Problem& problem, const State& state) {
  return problem.control_dof >= 0 ? state.u[problem.control_dof] : 0.0;
}

// --- columns shared by the files of a labelled run (Data has `label`) ----------------------

template <typename Data>
Column<Data> ProblemColumn() {
  return {"problem", "the problem's name (`contactbench list`, or a problem file's `name`)",
          [](const Data& d) -> Cell { return d.label.problem; }};
}
template <typename Data>
Column<Data> FormulationColumn(const char* meaning = "the formulation") {
  return {"formulation", meaning, [](const Data& d) -> Cell { return d.label.formulation; }};
}
template <typename Data>
Column<Data> SolverColumn() {
  return {"solver", "the equation solver or backend doing the formulation's work",
          [](const Data& d) -> Cell { return d.label.solver; }};
}
template <typename Data>
Column<Data> StartColumn() {
  return {"start", "warm, cold, near (`run --start near`) or guess:K (an FCLIB file's /guesses/K)",
          [](const Data& d) -> Cell { return d.label.start; }};
}
template <typename Data>
Column<Data> SettingsColumn() {
  return {"settings", "the settings that distinguish this formulation instance (eta case, ...)",
          [](const Data& d) -> Cell { return d.label.settings; }};
}
template <typename Data>
Column<Data> ModeColumn() {
  return {"mode",
          "run (`contactbench run`), replay or free (`contactbench compare --mode`), set "
          "(`compare --problem-dir`)",
          [](const Data& d) -> Cell { return d.label.mode; }};
}

// --- columns of a path record (Data = PathRow<Record>) --------------------------------------

template <typename Data>
Column<Data> StepColumn(const char* meaning) {
  return {"step", meaning, [](const Data& d) -> Cell { return d.record.step; }};
}
template <typename Data>
Column<Data> LambdaColumn() {
  return {"lambda", "the load parameter at the row's state",
          [](const Data& d) -> Cell { return d.record.state.lambda; }};
}
template <typename Data>
Column<Data> ControlDispColumn() {
  return {"control_disp", "the problem's control displacement at the row's state (0: none)",
          [](const Data& d) -> Cell { return ControlDisplacement(d.problem, d.record.state); }};
}
template <typename Data>
Column<Data> VerifiedColumn() {
  return {"verified",
          "the verdict: eq_res, comp_res, feas_res and step_res are finite and <= `--tol`",
          [](const Data& d) -> Cell { return d.record.verdict.verified; }};
}
template <typename Data>
Column<Data> EqResColumn() {
  return {"eq_res",
          "equilibrium residual (9): norm_inf(grad pi - lambda f - grad phi^T r) / "
          "max(1, norm_inf(lambda f))",
          [](const Data& d) -> Cell { return d.record.verdict.eq_res; }};
}
template <typename Data>
Column<Data> CompResColumn() {
  return {"comp_res", "complementarity residual (10)-(11): norm_inf(min(g/L, -r/R))",
          [](const Data& d) -> Cell { return d.record.verdict.comp_res; }};
}
template <typename Data>
Column<Data> FeasResColumn() {
  return {"feas_res", "feasibility residual: max(0, -min g/L, max r/R)",
          [](const Data& d) -> Cell { return d.record.verdict.feas_res; }};
}
template <typename Data>
Column<Data> StepResColumn() {
  return {"step_res", "abs(c), the residual of the dimensionless step constraint",
          [](const Data& d) -> Cell { return d.record.verdict.step_res; }};
}
template <typename Data>
Column<Data> IterationsColumn() {
  return {"iterations", "the solver's iterations",
          [](const Data& d) -> Cell { return d.record.result.counts.iterations; }};
}
template <typename Data>
Column<Data> TimeColumn() {
  return {"time_s", "wall time of the solve alone, seconds",
          [](const Data& d) -> Cell { return d.record.result.time_s; }};
}
template <typename Data>
Column<Data> StatusColumn() {
  return {"status",
          "the solver's own outcome: converged, limit_reached, time_limit (the solve ran out of "
          "time: a failed step), failed, stopped_by_caller (SIGINT/SIGTERM), not_run",
          [](const Data& d) -> Cell { return ToString(d.record.result.status); }};
}
template <typename Data>
Column<Data> ResultMessageColumn() {
  return {"message", "the solver's message",
          [](const Data& d) -> Cell { return d.record.result.message; }};
}

// --- columns of a state of a body --------------------------------------------------------------

Column<NodeRow> NodeStep() {
  return {"step", "the accepted step of the state",
          [](const NodeRow& d) -> Cell { return d.step; }};
}
Column<NodeRow> NodeLabel() {
  return {"label", "why the state was saved: step (`--save-every`), limit, bifurcation, final",
          [](const NodeRow& d) -> Cell { return d.label; }};
}
Column<NodeRow> NodeLambda() {
  return {"lambda", "the load parameter of the state",
          [](const NodeRow& d) -> Cell { return d.lambda; }};
}
std::vector<Column<NodeRow>> NodeColumns() {
  return {
      {"node",
       "the node: its id in the problem file (a Gmsh mesh: the node's tag); a named problem "
       "numbers its nodes from 0",
       [](const NodeRow& d) -> Cell { return d.node; }},
      {"x", "reference coordinate", [](const NodeRow& d) -> Cell { return d.reference[0]; }},
      {"y", "reference coordinate", [](const NodeRow& d) -> Cell { return d.reference[1]; }},
      {"z", "reference coordinate", [](const NodeRow& d) -> Cell { return d.reference[2]; }, true},
      {"ux", "displacement", [](const NodeRow& d) -> Cell { return d.moved[0] - d.reference[0]; }},
      {"uy", "displacement", [](const NodeRow& d) -> Cell { return d.moved[1] - d.reference[1]; }},
      {"uz", "displacement", [](const NodeRow& d) -> Cell { return d.moved[2] - d.reference[2]; },
       true},
  };
}

Column<PairRow> PairStep() {
  return {"step", "the accepted step of the state",
          [](const PairRow& d) -> Cell { return d.step; }};
}
Column<PairRow> PairLabel() {
  return {"label", "why the state was saved (as in `snapshots.csv`)",
          [](const PairRow& d) -> Cell { return d.label; }};
}
Column<PairRow> PairLambda() {
  return {"lambda", "the load parameter of the state",
          [](const PairRow& d) -> Cell { return d.lambda; }};
}
std::vector<Column<PairRow>> PairColumns() {
  return {
      {"pair", "the contact pair (0-based)", [](const PairRow& d) -> Cell { return d.pair; }},
      {"node", "the pair's node (as `node` in `snapshots.csv`)",
       [](const PairRow& d) -> Cell { return d.node; }},
      {"obstacle",
       "the pair's obstacle: its `id` in the problem file; a named problem numbers its "
       "obstacles from 0",
       [](const PairRow& d) -> Cell { return d.obstacle; }},
      {"g", "the gap g = -phi(u) (> 0 open, 0 in contact)",
       [](const PairRow& d) -> Cell { return d.gap; }},
      {"r", "the contact reaction (<= 0)", [](const PairRow& d) -> Cell { return d.reaction; }},
  };
}

template <typename T>
std::vector<T> Concatenate(std::vector<T> head, const std::vector<T>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

}  // namespace

// A schema table, one entry per column of steps.csv: longer than a function of steps would be,
// and read as a table.
const RecordSchema<AttemptRow>& StepsSchema() {
  using D = AttemptRow;
  static const RecordSchema<D> schema{
      "steps.csv",
      "",
      "attempt of a step (cut-back retries included)",
      {"run", "compare"},
      {
          ProblemColumn<D>(),
          FormulationColumn<D>(),
          SolverColumn<D>(),
          StartColumn<D>(),
          StepColumn<D>("the step being taken, from 1 (P1's single fixed-load solve: 1)"),
          LambdaColumn<D>(),
          ControlDispColumn<D>(),
          IterationsColumn<D>(),
          {"residual_evals", "evaluations of the formulation's residual",
           [](const D& d) -> Cell { return d.record.result.counts.residual_evals; }},
          {"jacobian_evals", "evaluations of its Jacobian",
           [](const D& d) -> Cell { return d.record.result.counts.jacobian_evals; }},
          {"linear_solves", "linear solves",
           [](const D& d) -> Cell { return d.record.result.counts.linear_solves; }},
          TimeColumn<D>(),
          {"found", "the solver's own claim: its stopping test was met (status converged)",
           [](const D& d) -> Cell { return d.record.result.status == Status::kConverged; }},
          VerifiedColumn<D>(),
          EqResColumn<D>(),
          CompResColumn<D>(),
          FeasResColumn<D>(),
          StepResColumn<D>(),
          {"fclib_error",
           "the FCLIB literature's error of the state the attempt reached, as an answer of the "
           "fixed-load problem at its lambda: natural-map residual relative to the data, as "
           "`fclib_error` of `problems.csv` (`src/verdict/natural_map_error.h`), for a problem "
           "read from an FCLIB file and an LCP; nan for every other problem (on a linear body it "
           "would cost a factorisation of K per step)",
           [](const D& d) -> Cell { return d.fclib_error; }},
          {"n_contact", "pairs in contact at the state the attempt reached",
           [](const D& d) -> Cell { return d.record.n_contact; }},
          {"kink", "kinks located between the previous accepted step and this one",
           [](const D& d) -> Cell { return d.record.kinks; }},
          {"attempt", "0 for the first attempt of the step, then one more per cut-back",
           [](const D& d) -> Cell { return d.record.attempt; }},
          {"accepted", "the attempt was verified and did not turn back: the path moved on",
           [](const D& d) -> Cell { return d.record.accepted; }},
          {"reversed", "the answer turned back on the path (rejected by the guard)",
           [](const D& d) -> Cell { return d.record.reversed; }},
          {"constraint",
           "the step constraint: arc-length (33), fixed-load, displacement, kink, hyperplane (the "
           "step off a bifurcation point)",
           [](const D& d) -> Cell { return ToString(d.record.kind); }},
          {"arc_length", "theta of (33) used by the attempt (after cut-backs)",
           [](const D& d) -> Cell { return d.record.arc_length; }},
          StatusColumn<D>(),
          SettingsColumn<D>(),
          {"length_scale", "L, the length scale of the contact unknowns (docs/method.md section 2)",
           [](const D& d) -> Cell { return d.problem.scales.length; }},
          {"force_scale", "R, the force scale of the contact unknowns",
           [](const D& d) -> Cell { return d.problem.scales.force; }},
          ModeColumn<D>(),
          {"unstable_modes",
           "negative eigenvalues of the stiffness on the motions that keep the closed contacts "
           "closed (0: stable; -1: not computed)",
           [](const D& d) -> Cell { return d.record.stability; }},
          {"branch", "0 on the initial branch, then +1 per branch switch",
           [](const D& d) -> Cell { return d.record.branch; }},
          {"branch_switch", "this step left a bifurcation point onto the other branch",
           [](const D& d) -> Cell { return d.record.branch_switch; }},
          {"tolerance", "the verdict's tolerance the attempt was judged to (`--tol`)",
           [](const D& d) -> Cell { return d.record.verdict.tolerance; }},
          {"time_min_s",
           "the fastest of the solve's timed repetitions (`compare --repeat`), seconds",
           [](const D& d) -> Cell { return d.record.result.time_min_s; }},
          {"time_max_s", "the slowest of them, seconds",
           [](const D& d) -> Cell { return d.record.result.time_max_s; }},
          {"time_samples",
           "how many solves were timed (time_s is their median): 1, or `compare --repeat N`'s N",
           [](const D& d) -> Cell { return d.record.result.time_samples; }},
          {"repeats_agree",
           "every repetition gave the first solve's answer (the one judged): the same status and "
           "iterations, the point within `--tol` (relative)",
           [](const D& d) -> Cell { return d.record.result.repeats_disagreement.empty(); }},
          ResultMessageColumn<D>(),
      }};
  return schema;
}

const RecordSchema<IterationRow>& IterationsSchema() {
  using D = IterationRow;
  static const RecordSchema<D> schema{
      "iterations.csv",
      "",
      "solver iteration of a step attempt",
      {"run", "compare"},
      {
          ProblemColumn<D>(),
          FormulationColumn<D>(),
          SolverColumn<D>(),
          StartColumn<D>(),
          {"step", "the step (as in `steps.csv`)",
           [](const D& d) -> Cell { return d.attempt.step; }},
          {"attempt", "the attempt (as in `steps.csv`)",
           [](const D& d) -> Cell { return d.attempt.attempt; }},
          {"iteration", "the iteration", [](const D& d) -> Cell { return d.iteration.iteration; }},
          {"merit", "1/2 norm(F)^2 of the formulation's own (scaled) system",
           [](const D& d) -> Cell { return d.iteration.merit; }},
          {"residual_inf", "norm_inf(F) of the formulation's own system",
           [](const D& d) -> Cell { return d.iteration.residual_inf; }},
          {"comp_res", "norm_inf(min(g/L, -r/R)) at the iterate where cheap, else nan",
           [](const D& d) -> Cell { return d.iteration.comp_res; }},
          {"step_length",
           "the iteration's step: the line-search step (Newton, quasi-Newton), the norm of the "
           "trust-region step (dogleg), alpha_pr (Ipopt), the norm of the change of x (NLopt)",
           [](const D& d) -> Cell { return d.iteration.step_length; }},
          ModeColumn<D>(),
      }};
  return schema;
}

const RecordSchema<KinkRow>& KinksSchema() {
  using D = KinkRow;
  static const RecordSchema<D> schema{
      "kinks.csv",
      "",
      "located kink (a pair with g = r = 0, docs/method.md section 6; compare: the reference "
      "path's)",
      {"run", "compare"},
      {
          ProblemColumn<D>(),
          FormulationColumn<D>(
              "the formulation; `reference:NAME` for the reference path of a replay comparison"),
          StartColumn<D>(),
          StepColumn<D>("located between the accepted steps step - 1 and step"),
          {"pair", "the pair whose contact status changed",
           [](const D& d) -> Cell { return d.record.pair; }},
          LambdaColumn<D>(),
          ControlDispColumn<D>(),
          VerifiedColumn<D>(),
          {"between", "the kink lies on the path between the two bracketing steps",
           [](const D& d) -> Cell { return d.record.between; }},
          IterationsColumn<D>(),
          EqResColumn<D>(),
          CompResColumn<D>(),
          FeasResColumn<D>(),
          StepResColumn<D>(),
          TimeColumn<D>(),
          StatusColumn<D>(),
          ResultMessageColumn<D>(),
      }};
  return schema;
}

const RecordSchema<CriticalRow>& CriticalSchema() {
  using D = CriticalRow;
  static const RecordSchema<D> schema{
      "critical.csv",
      "",
      "limit point (lambda turns), bifurcation point (located by bisection), or a change of "
      "the unstable modes with a contact change",
      {"run", "compare"},
      {
          ProblemColumn<D>(),
          FormulationColumn<D>(),
          StartColumn<D>(),
          StepColumn<D>("found between the accepted steps step - 1 and step"),
          {"kind", "limit, bifurcation or stability_change",
           [](const D& d) -> Cell { return ToString(d.record.kind); }},
          {"nonsmooth", "limit point: a kink was located in one of the two steps around it",
           [](const D& d) -> Cell { return d.record.nonsmooth; }},
          LambdaColumn<D>(),
          ControlDispColumn<D>(),
          {"located", "bifurcation point: bracketed to the bifurcation tolerance",
           [](const D& d) -> Cell { return d.record.located; }},
          {"bisections", "bisections of the arc length that located it",
           [](const D& d) -> Cell { return d.record.bisections; }},
          VerifiedColumn<D>(),
          EqResColumn<D>(),
          CompResColumn<D>(),
          {"switched", "the path left this point onto the other branch",
           [](const D& d) -> Cell { return d.record.switched; }},
          {"message", "what was found, or why it could not be located",
           [](const D& d) -> Cell { return d.record.message; }},
      }};
  return schema;
}

const RecordSchema<NodeRow>& SolutionSchema() {
  static const RecordSchema<NodeRow> schema{"solution.csv",
                                            "a body",
                                            "node at the last accepted state",
                                            {"run"},
                                            Concatenate({NodeStep()}, NodeColumns())};
  return schema;
}

const RecordSchema<ComplementarityRow>& ComplementaritySolutionSchema() {
  using D = ComplementarityRow;
  static const RecordSchema<D> schema{
      "solution.csv",
      "a complementarity problem (LCP)",
      "unknown at the last accepted state",
      {"run"},
      {
          {"step", "the accepted step of the state", [](const D& d) -> Cell { return d.step; }},
          {"index", "the unknown (0-based)", [](const D& d) -> Cell { return d.index; }},
          {"z", "the unknown z_i", [](const D& d) -> Cell { return d.z; }},
          {"w", "its complement w_i = (M z + q)_i", [](const D& d) -> Cell { return d.w; }},
      }};
  return schema;
}

const RecordSchema<PairRow>& ContactsSchema() {
  static const RecordSchema<PairRow> schema{
      "contacts.csv",
      "",
      "contact pair at the last accepted state",
      {"run"},
      Concatenate(Concatenate({PairStep()}, PairColumns()), {PairLambda()})};
  return schema;
}

const RecordSchema<NodeRow>& SnapshotsSchema() {
  static const RecordSchema<NodeRow> schema{
      "snapshots.csv",
      "",
      "node x saved state (every `--save-every` steps, each limit and bifurcation point, the "
      "final state)",
      {"run"},
      Concatenate({NodeStep(), NodeLabel(), NodeLambda()}, NodeColumns())};
  return schema;
}

const RecordSchema<PairRow>& SnapshotContactsSchema() {
  static const RecordSchema<PairRow> schema{
      "snapshot_contacts.csv",
      "",
      "contact pair x saved state",
      {"run"},
      Concatenate({PairStep(), PairLabel(), PairLambda()}, PairColumns())};
  return schema;
}

const RecordSchema<CellCornerRow>& CellsSchema() {
  using D = CellCornerRow;
  static const RecordSchema<D> schema{
      "cells.csv",
      "",
      "corner of an element (to draw the mesh from the CSV files alone)",
      {"run"},
      {
          {"cell", "the element (a truss member or a Q4 element, 0-based)",
           [](const D& d) -> Cell { return d.cell; }},
          {"corner", "the corner within the element", [](const D& d) -> Cell { return d.corner; }},
          {"node", "the corner's node (as `node` in `snapshots.csv`)",
           [](const D& d) -> Cell { return d.node; }},
      }};
  return schema;
}

const RecordSchema<ParameterRow>& ParametersSchema() {
  using D = ParameterRow;
  static const RecordSchema<D> schema{
      "parameters.csv",
      "",
      "problem parameter (reconstruction choices included), then the model's sizes num_dofs "
      "(d) and num_pairs (nc)",
      {"run"},
      {
          {"problem", "the problem's name", [](const D& d) -> Cell { return d.problem; }},
          {"name", "the parameter (`--set NAME=VALUE`)", [](const D& d) -> Cell { return d.name; }},
          {"value", "its value as used", [](const D& d) -> Cell { return d.value; }},
          {"doc", "what it is", [](const D& d) -> Cell { return d.doc; }},
      }};
  return schema;
}

const RecordSchema<RunOutcomeRow>& RunsSchema() {
  using D = RunOutcomeRow;
  static const RecordSchema<D> schema{
      "runs.csv",
      "",
      "formulation x start of a comparison",
      {"compare"},
      {
          ProblemColumn<D>(),
          FormulationColumn<D>(),
          SolverColumn<D>(),
          StartColumn<D>(),
          ModeColumn<D>(),
          SettingsColumn<D>(),
          {"status",
           "the path's outcome (as `status` in `steps.csv`), or skipped: the formulation cannot "
           "express the step constraint or refused the problem",
           [](const D& d) -> Cell { return d.status; }},
          {"attempts", "step attempts made", [](const D& d) -> Cell { return d.attempts; }},
          {"accepted", "steps accepted", [](const D& d) -> Cell { return d.accepted; }},
          {"message", "the path's message, or why it was skipped",
           [](const D& d) -> Cell { return d.message; }},
          {"time_limit_s", "the time limit per solve, seconds (`--time-limit`; 0: none)",
           [](const D& d) -> Cell { return d.time_limit_s; }},
          {"tolerance", "the verdict's tolerance (`--tol`)",
           [](const D& d) -> Cell { return d.tolerance; }},
      }};
  return schema;
}

namespace {

// A problem set's solve: what its attempt says, or `skipped` for a formulation that refused.
template <typename Value>
Cell OfAttempt(const ProblemSetRow& d, Value (*value)(const StepAttempt&), const Cell& otherwise) {
  return d.attempt != nullptr ? Cell(value(*d.attempt)) : otherwise;
}

std::string_view ProblemSetStatus(const ProblemSetRow& d) {
  if (d.problem == nullptr) return "unreadable";
  if (d.attempt == nullptr) return "skipped";
  return d.attempt->accepted ? "verified" : "failed";
}

}  // namespace

// A schema table, one entry per column of problems.csv (read as a table, as StepsSchema).
const RecordSchema<ProblemSetRow>& ProblemSetSchema() {
  using D = ProblemSetRow;
  using A = const StepAttempt&;
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  static const RecordSchema<D> schema{
      "problems.csv",
      "",
      "problem x formulation x start of a problem set (`compare --problem-dir`)",
      {"compare"},
      {
          ProblemColumn<D>(),
          {"source", "the problem file", [](const D& d) -> Cell { return d.source; }},
          FormulationColumn<D>(),
          SolverColumn<D>(),
          StartColumn<D>(),
          SettingsColumn<D>(),
          {"d", "unknowns of the body (of an LCP: its size; 0 when unreadable)",
           [](const D& d) -> Cell { return d.problem ? d.problem->model->num_dofs() : 0; }},
          {"nc", "contact pairs (0 when unreadable)",
           [](const D& d) -> Cell { return d.problem ? d.problem->model->num_pairs() : 0; }},
          {"status",
           "verified (the verdict verified the answer at `tolerance`), failed, skipped (the "
           "formulation refused the problem; `message` says why), or unreadable (the file is no "
           "fixed-load problem the suite reads: one row for the file, with no formulation or "
           "start, `message` says why)",
           [](const D& d) -> Cell { return ProblemSetStatus(d); }},
          {"found", "what the solver claims (as `found` in `steps.csv`; empty when skipped)",
           [](const D& d) -> Cell {
             return OfAttempt<const char*>(
                 d, [](A a) { return ToString(a.result.status); }, "");
           }},
          {"iterations", "outer iterations (the counting rule of docs/comparison.md)",
           [](const D& d) -> Cell {
             return OfAttempt<int>(
                 d, [](A a) { return a.result.counts.iterations; }, 0);
           }},
          {"time_s", "wall time of the solve, seconds: the median of `time_samples` solves",
           [](const D& d) -> Cell {
             return OfAttempt<double>(
                 d, [](A a) { return a.result.time_s; }, kNone);
           }},
          {"time_min_s", "the fastest of them, seconds",
           [](const D& d) -> Cell {
             return OfAttempt<double>(
                 d, [](A a) { return a.result.time_min_s; }, kNone);
           }},
          {"time_max_s", "the slowest of them, seconds",
           [](const D& d) -> Cell {
             return OfAttempt<double>(
                 d, [](A a) { return a.result.time_max_s; }, kNone);
           }},
          {"time_samples", "how many solves were timed (`--repeat`; 0 when skipped)",
           [](const D& d) -> Cell {
             return OfAttempt<int>(
                 d, [](A a) { return a.result.time_samples; }, 0);
           }},
          {"repeats_agree", "every repetition gave the first solve's answer (the one judged)",
           [](const D& d) -> Cell {
             return OfAttempt<bool>(
                 d, [](A a) { return a.result.repeats_disagreement.empty(); }, true);
           }},
          {"eq_res", "the verdict's equilibrium residual (as in `steps.csv`)",
           [](const D& d) -> Cell {
             return OfAttempt<double>(
                 d, [](A a) { return a.verdict.eq_res; }, kNone);
           }},
          {"comp_res", "the verdict's complementarity residual (as in `steps.csv`)",
           [](const D& d) -> Cell {
             return OfAttempt<double>(
                 d, [](A a) { return a.verdict.comp_res; }, kNone);
           }},
          {"fclib_error",
           "the FCLIB literature's error of the answer: natural-map residual relative to the "
           "data (`src/verdict/natural_map_error.h`; nan for a nonlinear problem, or when "
           "skipped or unreadable)",
           [](const D& d) -> Cell { return d.fclib_error; }},
          {"time_limit_s", "the time limit per solve, seconds (`--time-limit`; 0: none)",
           [](const D& d) -> Cell { return d.time_limit_s; }},
          {"tolerance", "the verdict's tolerance (`--tol`)",
           [](const D& d) -> Cell { return d.tolerance; }},
          {"message",
           "the solver's message, why the formulation refused the problem, or why the file "
           "could not be read",
           [](const D& d) -> Cell { return d.message; }},
      }};
  return schema;
}

std::vector<RecordDoc> RecordDocs() {
  return {StepsSchema().Doc(),     IterationsSchema().Doc(), KinksSchema().Doc(),
          CriticalSchema().Doc(),  SolutionSchema().Doc(),   ComplementaritySolutionSchema().Doc(),
          ContactsSchema().Doc(),  SnapshotsSchema().Doc(),  SnapshotContactsSchema().Doc(),
          CellsSchema().Doc(),     ParametersSchema().Doc(), RunsSchema().Doc(),
          ProblemSetSchema().Doc()};
}

}  // namespace cb::harness
