#include "formulations/petsc/petsc_mcp.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cb {

namespace {

// Row i of the MCP in terms of the step equations' rows (see the top of the header): the pairs'
// rows are (S2 + S3, S2); every other row is its own.
struct Sources {
  int a = -1;
  int b = -1;
};
Sources RowSources(const StepEquationLayout& l, int i) {
  if (i >= l.g() && i < l.g() + l.nc) return {i, i + l.nc};   // S2 + S3
  if (i >= l.r() && i < l.r() + l.nc) return {i - l.nc, -1};  // S2
  return {i, -1};
}

}  // namespace

bool McpFunction(McpStepEquations& equations, const Vec& x, Vec* f) {
  const bool finite = equations.Residual(x, f);
  const StepEquationLayout& l = equations.layout();
  for (int p = 0; p < l.nc; ++p) {
    const double gaps = (*f)[l.g() + p];      // S2: (30) / L
    const double reaction = (*f)[l.r() + p];  // S3: -r^_p (or the kink row)
    (*f)[l.g() + p] = gaps + reaction;
    (*f)[l.r() + p] = gaps;
  }
  return finite;
}

McpBounds MakeMcpBounds(const StepProblem& step) {
  const StepEquationLayout l{step.num_dofs(), step.num_pairs(), false};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  McpBounds b{Vec::Constant(l.size(), -kInf), Vec::Constant(l.size(), kInf)};
  b.lower.segment(l.g(), l.nc).setZero();  // g^ >= 0, (11)
  if (step.constraint.kind == ConstraintKind::kKink) {
    b.lower[l.g() + step.constraint.index] = -kInf;  // the kink pair's rows are equalities
  }
  return b;
}

Vec MakeMcpStart(const StepProblem& step, const StartPoint& start, const McpBounds& bounds) {
  const StepEquationLayout l{step.num_dofs(), step.num_pairs(), false};
  Vec x = MakeStepEquationStart(step, start, l.size());
  if (start.kind == StartKind::kCold) {
    x.segment(l.g(), l.nc).setZero();
    x.segment(l.r(), l.nc).setConstant(-1.0);
  }
  for (int p = 0; p < l.nc; ++p) {
    const bool closed = x[l.r() + p] < -kTieReaction && std::isfinite(bounds.lower[l.g() + p]);
    if (closed) x[l.g() + p] = bounds.lower[l.g() + p];  // see the header
  }
  x = x.cwiseMax(bounds.lower).cwiseMin(bounds.upper);
  for (int p = 0; p < l.nc; ++p) {
    const bool tie = x[l.g() + p] == bounds.lower[l.g() + p] && x[l.r() + p] == 0.0;
    if (tie) x[l.r() + p] = -kTieReaction;  // see the header
  }
  return x;
}

double McpNaturalResidual(const Vec& x, const Vec& f, const McpBounds& bounds) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    // mid(x - l, F, x - u): F clipped to [x - u, x - l].
    const double natural = std::clamp(f[i], x[i] - bounds.upper[i], x[i] - bounds.lower[i]);
    worst = std::max(worst, std::abs(natural));
  }
  return worst;
}

McpRowMap MakeMcpRowMap(const StepEquationLayout& layout, const SpMat& s) {
  McpRowMap map;
  map.size = static_cast<int>(s.rows());
  const int nnz = static_cast<int>(s.nonZeros());
  map.csc_start.assign(s.outerIndexPtr(), s.outerIndexPtr() + s.outerSize() + 1);
  map.csc_rows.assign(s.innerIndexPtr(), s.innerIndexPtr() + nnz);
  // The step equations' rows as (column, value index) lists, columns ascending.
  std::vector<std::vector<std::pair<int, int>>> rows(map.size);
  for (int j = 0; j < s.cols(); ++j) {
    for (int k = map.csc_start[j]; k < map.csc_start[j + 1]; ++k) {
      rows[map.csc_rows[k]].emplace_back(j, k);
    }
  }
  map.row_start.assign(1, 0);
  for (int i = 0; i < map.size; ++i) {
    const Sources from = RowSources(layout, i);
    const auto& a = rows[from.a];
    static const std::vector<std::pair<int, int>> kNone;
    const auto& b = from.b >= 0 ? rows[from.b] : kNone;
    std::size_t ia = 0, ib = 0;
    bool diagonal = false;
    auto add = [&](int column, int first, int second) {
      if (!diagonal && column > i) {  // a structural zero on the diagonal (see the header)
        map.columns.push_back(i);
        map.first.push_back(-1);
        map.second.push_back(-1);
      }
      diagonal = diagonal || column >= i;
      map.columns.push_back(column);
      map.first.push_back(first);
      map.second.push_back(second);
    };
    while (ia < a.size() || ib < b.size()) {  // the union of the two rows, merged
      const int ca = ia < a.size() ? a[ia].first : s.cols();
      const int cb = ib < b.size() ? b[ib].first : s.cols();
      if (ca <= cb) {
        add(ca, a[ia].second, ca == cb ? b[ib].second : -1);
      } else {
        add(cb, b[ib].second, -1);
      }
      if (ca <= cb) ++ia;
      if (cb <= ca) ++ib;
    }
    if (!diagonal) {  // every column of the row lies left of the diagonal
      map.columns.push_back(i);
      map.first.push_back(-1);
      map.second.push_back(-1);
    }
    map.row_start.push_back(static_cast<int>(map.columns.size()));
  }
  return map;
}

bool SamePattern(const McpRowMap& map, const SpMat& s) {
  if (s.rows() != map.size || s.cols() != map.size ||
      s.nonZeros() != static_cast<Eigen::Index>(map.csc_rows.size())) {
    return false;
  }
  return std::equal(map.csc_start.begin(), map.csc_start.end(), s.outerIndexPtr()) &&
         std::equal(map.csc_rows.begin(), map.csc_rows.end(), s.innerIndexPtr());
}

void FillMcpValues(const McpRowMap& map, const SpMat& s, double* values) {
  const double* v = s.valuePtr();
  for (std::size_t slot = 0; slot < map.first.size(); ++slot) {
    values[slot] = (map.first[slot] >= 0 ? v[map.first[slot]] : 0.0) +
                   (map.second[slot] >= 0 ? v[map.second[slot]] : 0.0);
  }
}

SpMat McpJacobian(const McpRowMap& map, const SpMat& s) {
  std::vector<double> values(map.columns.size());
  FillMcpValues(map, s, values.data());
  std::vector<Triplet> entries;
  entries.reserve(values.size());
  for (int i = 0; i < map.size; ++i) {
    for (int k = map.row_start[i]; k < map.row_start[i + 1]; ++k) {
      entries.emplace_back(i, map.columns[k], values[k]);
    }
  }
  SpMat m(map.size, map.size);
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

}  // namespace cb
