// The PETSc formulations' step as rows (common/step_rows.h): the MCP of petsc_mcp.h within its
// bounds from MakeMcpStart, its Jacobian in column-compressed form for a solver outside PETSc's
// serial adapter (the distributed backend), made once per pattern of the step equations'
// Jacobian and afterwards filled in place (the matrix of the previous call, passed again).
#include <algorithm>
#include <memory>
#include <vector>

#include "formulations/petsc/petsc_mcp.h"

namespace cb {

namespace {

class McpJacobianInPlace {
 public:
  void Fill(McpStepEquations& system, const Vec& y, SpMat* jacobian) {
    system.Jacobian(y, &s_);
    if (rows_.size == 0 || !SamePattern(rows_, s_) || jacobian != shaped_) {
      rows_ = MakeMcpRowMap(system.layout(), s_);
      *jacobian = McpJacobian(rows_, s_);
      shaped_ = jacobian;
      StoragePositions(*jacobian);
    }
    FillMcpValues(rows_, s_, values_.data());
    double* to = jacobian->valuePtr();
    for (std::size_t k = 0; k < values_.size(); ++k) to[positions_[k]] = values_[k];
  }

 private:
  // Where the map's entries (row by row) lie in the column-compressed storage of `m`.
  void StoragePositions(const SpMat& m) {
    positions_.clear();
    for (int i = 0; i < rows_.size; ++i) {
      for (int k = rows_.row_start[i]; k < rows_.row_start[i + 1]; ++k) {
        const int column = rows_.columns[k];
        const int* first = m.innerIndexPtr() + m.outerIndexPtr()[column];
        const int* last = m.innerIndexPtr() + m.outerIndexPtr()[column + 1];
        positions_.push_back(
            static_cast<int>(std::lower_bound(first, last, i) - m.innerIndexPtr()));
      }
    }
    values_.assign(positions_.size(), 0.0);
  }

  SpMat s_;
  McpRowMap rows_;
  const SpMat* shaped_ = nullptr;
  std::vector<int> positions_;
  std::vector<double> values_;
};

// The system and its Jacobian's filler, which the rows keep alive together.
struct McpRowsState {
  McpRowsState(const StepProblem& local, std::shared_ptr<StepEquationSystem::PatternCache> cache)
      : system(local, std::move(cache)) {}
  McpStepEquations system;
  McpJacobianInPlace jacobian;
};

}  // namespace

StepRows McpRows(const StepProblem& step, const StepProblem& local, const StartPoint& start,
                 std::shared_ptr<StepEquationSystem::PatternCache> cache) {
  auto state = std::make_shared<McpRowsState>(local, std::move(cache));
  McpRowsState* s = state.get();
  McpBounds bounds = MakeMcpBounds(step);
  StepRows rows;
  rows.residual = [s](const Vec& y, Vec* f) { return McpFunction(s->system, y, f); };
  rows.jacobian = [s](const Vec& y, SpMat* jacobian) { s->jacobian.Fill(s->system, y, jacobian); };
  rows.layout = s->system.layout();
  rows.start = MakeMcpStart(step, start, bounds);
  rows.lower = std::move(bounds.lower);
  rows.upper = std::move(bounds.upper);
  rows.owner = std::move(state);
  return rows;
}

}  // namespace cb
