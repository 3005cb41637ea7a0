// "kind": "lcp": a linear complementarity problem 0 <= z _|_ w = M z + q >= 0, M dense (rows)
// or sparse (entries) (docs/problem-files.md).
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

#include "io/input_error.h"
#include "io/problem_file_kinds.h"
#include "io/problem_file_loading.h"
#include "model/complementarity_model.h"

namespace cb::io::reading {

namespace {

// M as an array of rows: every row as long as there are rows.
Eigen::Index ReadDenseMatrix(const JsonNode& m, std::vector<Triplet>* entries) {
  const auto rows = m.Items();
  const auto n = static_cast<Eigen::Index>(rows.size());
  if (n == 0) m.Fail("must not be empty");
  for (Eigen::Index i = 0; i < n; ++i) {
    const JsonNode& row = rows[i];
    if (static_cast<Eigen::Index>(row.Size()) != n) {
      row.Fail("has " + std::to_string(row.Size()) + " entries, M has " + std::to_string(n) +
               " rows: M must be square");
    }
    for (Eigen::Index j = 0; j < n; ++j) {
      const double v = row.At(j).Number();
      if (v != 0.0) entries->emplace_back(static_cast<int>(i), static_cast<int>(j), v);
    }
  }
  return n;
}

// M as {rows, cols, entries: [[row, col, value]]}: square, each entry inside and given once.
Eigen::Index ReadSparseMatrix(const JsonNode& m, std::vector<Triplet>* entries) {
  m.ExpectObject({"rows", "cols", "entries"});
  const Eigen::Index n = m.Field("rows").PositiveInt();
  const int cols = m.Field("cols").PositiveInt();
  if (cols != n) {
    m.Field("cols").Fail("M must be square, got " + std::to_string(n) + " x " +
                         std::to_string(cols));
  }
  std::map<std::pair<std::int64_t, std::int64_t>, std::size_t> seen;
  const auto list = m.Field("entries").Items();
  for (std::size_t k = 0; k < list.size(); ++k) {
    const JsonNode& e = list[k];
    if (e.Size() != 3) e.Fail("an entry is [row, col, value] (0-based)");
    const std::int64_t i = e.At(0).Integer();
    const std::int64_t j = e.At(1).Integer();
    if (i < 0 || i >= n)
      e.At(0).Fail("row " + std::to_string(i) + " outside 0.." + std::to_string(n - 1));
    if (j < 0 || j >= n)
      e.At(1).Fail("column " + std::to_string(j) + " outside 0.." + std::to_string(n - 1));
    auto [it, inserted] = seen.emplace(std::make_pair(i, j), k);
    if (!inserted) {
      e.Fail("entry (" + std::to_string(i) + ", " + std::to_string(j) + ") given twice (also " +
             m.where() + "/entries/" + std::to_string(it->second) + ")");
    }
    entries->emplace_back(static_cast<int>(i), static_cast<int>(j), e.At(2).Number());
  }
  return n;
}

// The model of "M" and "q".
std::shared_ptr<ComplementarityModel> ReadLcpModel(const JsonNode& root) {
  const JsonNode m = root.Field("M");
  std::vector<Triplet> entries;
  Eigen::Index n = 0;
  if (m.value().is_array()) {
    n = ReadDenseMatrix(m, &entries);
  } else if (m.value().is_object()) {
    n = ReadSparseMatrix(m, &entries);
  } else {
    m.Fail("expected an array of rows (dense) or an object {rows, cols, entries} (sparse)");
  }
  const JsonNode qn = root.Field("q");
  const Vec q = qn.AnyVector();
  if (q.size() != n) {
    qn.Fail("has " + std::to_string(q.size()) + " entries, M is " + std::to_string(n) + " x " +
            std::to_string(n));
  }
  SpMat matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return std::make_shared<ComplementarityModel>(ComplementarityModel::Lcp(matrix, q));
}

}  // namespace

Problem ReadLcp(const JsonNode& root, const std::string& file, const Settings& settings) {
  root.ExpectObject({"kind", "version", "name", "description", "units", "source", "length_scale",
                     "force_scale", "analysis", "M", "q"});
  if (auto a = root.Optional("analysis")) {
    if (a->String() != "fixed-load") {
      a->Fail("an LCP is one fixed-load solve (lambda = 0): must be \"fixed-load\"");
    }
  }
  auto model = ReadLcpModel(root);
  const auto n = model->num_dofs();
  double length = 1.0, force = 1.0;
  model->DataScales(&length, &force);  // the default: the sizes of z and w the data imply
  if (auto l = root.Optional("length_scale")) length = l->Positive();
  if (auto f = root.Optional("force_scale")) force = f->Positive();
  Parameters p = RunParameters(length, force, Loading{}, true);
  ApplySettings(file, settings, &p);

  Problem problem;
  problem.model = std::move(model);
  try {
    problem.scales = ScalesFrom(p);
  } catch (const std::invalid_argument& e) {
    throw InputError(file, "", e.what());  // a scale the data imply: none usable
  }
  problem.parameters = p;
  problem.loading = LoadingKind::kFixedLoad;
  problem.load = 0.0;  // f = 0: (29) at lambda = 0 is w = M z + q = -r
  problem.steps = 1;
  problem.description = OptionalString(root, "description", "LCP, n = " + std::to_string(n));
  return problem;
}

}  // namespace cb::io::reading
