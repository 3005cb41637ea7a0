// The record files of `contactbench run` and `compare` (COMPARISON.md): for each, the data of
// one row and its schema (record_schema.h). The writers (records.h, snapshots.h) fill the data;
// the schema alone decides the columns, their order and their meaning.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "harness/record_schema.h"
#include "path/path.h"
#include "problems/problem.h"

namespace cb::harness {

// Identifies a run in every row.
struct RunLabel {
  std::string problem;
  std::string formulation;
  std::string solver;
  std::string settings;
  std::string start;
  std::string mode;  // "run" (contactbench run), "replay" or "free" (contactbench compare)
};

// A record of the path driver (a step attempt, a kink, a critical point) of a labelled run.
template <typename Record>
struct PathRow {
  const RunLabel& label;
  const Problem& problem;
  const Record& record;
};
// A step attempt, with the FCLIB error of the state it reached (natural_map_error.h; NaN
// where it is not defined).
struct AttemptRow {
  const RunLabel& label;
  const Problem& problem;
  const StepAttempt& record;
  double fclib_error = 0.0;
};
using KinkRow = PathRow<KinkRecord>;
using CriticalRow = PathRow<CriticalPointRecord>;

// One iteration of a step attempt's solve.
struct IterationRow {
  const RunLabel& label;
  const StepAttempt& attempt;
  const IterationRecord& iteration;
};

// A node of a body at a state; `label` and `lambda` say which saved state. `node` is the
// node's id (Problem::node_ids).
struct NodeRow {
  int step = 0;
  std::string_view label;
  double lambda = 0.0;
  std::int64_t node = 0;
  Point reference;
  Point moved;
};

// A contact pair at a state; `label` says which saved state. `node` and `obstacle` are the
// ids of Problem::node_ids and obstacle_ids.
struct PairRow {
  int step = 0;
  std::string_view label;
  double lambda = 0.0;
  int pair = 0;
  std::int64_t node = 0;
  std::string obstacle;
  double gap = 0.0;
  double reaction = 0.0;
};

// One unknown of a complementarity problem (an LCP) and its complement.
struct ComplementarityRow {
  int step = 0;
  int index = 0;
  double z = 0.0;
  double w = 0.0;
};

// One corner of an element; `node` is the node's id.
struct CellCornerRow {
  int cell = 0;
  int corner = 0;
  std::int64_t node = 0;
};

// One parameter of a problem (or a size of its model).
struct ParameterRow {
  std::string_view problem;
  std::string_view name;
  std::string_view value;
  std::string_view doc;
};

// The outcome of one formulation x start of a comparison.
struct RunOutcomeRow {
  const RunLabel& label;
  std::string_view status;
  int attempts = 0;
  int accepted = 0;
  std::string_view message;
  double time_limit_s = 0.0;
  double tolerance = 0.0;
};

// One formulation x start on one problem of a problem set (`compare --problem-dir`): the
// fixed-load solve's attempt, or none when the formulation refused the problem; or a file of
// the set that could not be read (no problem, no attempt, `message` says why).
struct ProblemSetRow {
  const RunLabel& label;
  std::string_view source;               // the problem file
  const Problem* problem = nullptr;      // nullptr: the file could not be read
  const StepAttempt* attempt = nullptr;  // nullptr: skipped (or unreadable)
  double fclib_error = 0.0;              // natural_map_error.h (NaN: not defined)
  std::string_view message;              // the solve's message, or why it was skipped
  double time_limit_s = 0.0;
  double tolerance = 0.0;
};

const RecordSchema<AttemptRow>& StepsSchema();
const RecordSchema<IterationRow>& IterationsSchema();
const RecordSchema<KinkRow>& KinksSchema();
const RecordSchema<CriticalRow>& CriticalSchema();
const RecordSchema<NodeRow>& SolutionSchema();
const RecordSchema<ComplementarityRow>& ComplementaritySolutionSchema();
const RecordSchema<PairRow>& ContactsSchema();
const RecordSchema<NodeRow>& SnapshotsSchema();
const RecordSchema<PairRow>& SnapshotContactsSchema();
const RecordSchema<CellCornerRow>& CellsSchema();
const RecordSchema<ParameterRow>& ParametersSchema();
const RecordSchema<RunOutcomeRow>& RunsSchema();
const RecordSchema<ProblemSetRow>& ProblemSetSchema();

// Every record file's documentation, in the order of docs/records.md.
std::vector<RecordDoc> RecordDocs();

}  // namespace cb::harness
