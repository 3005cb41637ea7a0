#include "io/problem_file_nodes.h"

#include "io/directions.h"

namespace cb::io::reading {

int NodeTable::Find(const JsonNode& ref) const {
  const std::int64_t id = ref.Integer();
  auto it = index.find(id);
  if (it == index.end()) ref.Fail("unknown node id " + std::to_string(id));
  return it->second;
}

std::optional<std::pair<int, int>> CoincidentNodes(const Mat& xy) {
  const Eigen::Index n = xy.rows();
  if (n < 2) return std::nullopt;
  const double extent = (xy.colwise().maxCoeff() - xy.colwise().minCoeff()).norm();
  const double tolerance = 1e-12 * extent;
  std::vector<int> by_x(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) by_x[static_cast<std::size_t>(k)] = k;
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return xy(a, 0) < xy(b, 0); });
  for (std::size_t i = 0; i < by_x.size(); ++i) {
    for (std::size_t j = i + 1; j < by_x.size() && xy(by_x[j], 0) - xy(by_x[i], 0) <= tolerance;
         ++j) {
      if ((xy.row(by_x[i]) - xy.row(by_x[j])).norm() <= tolerance) {
        return std::make_pair(std::min(by_x[i], by_x[j]), std::max(by_x[i], by_x[j]));
      }
    }
  }
  return std::nullopt;
}

NodeTable ReadNodes(const JsonNode& nodes, int dim) {
  NodeTable t;
  const auto items = nodes.Items();
  if (items.empty()) nodes.Fail("must list at least one node");
  t.coordinates.resize(static_cast<Eigen::Index>(items.size()), dim);
  for (std::size_t k = 0; k < items.size(); ++k) {
    items[k].ExpectObject({"id", "x"});
    const JsonNode id = items[k].Field("id");
    const std::int64_t value = id.Integer();
    auto [it, inserted] = t.index.emplace(value, static_cast<int>(k));
    if (!inserted) {
      id.Fail("duplicate node id " + std::to_string(value) + " (also /nodes/" +
              std::to_string(it->second) + ")");
    }
    t.ids.push_back(value);
    t.coordinates.row(static_cast<Eigen::Index>(k)) = items[k].Field("x").Vector(dim).transpose();
  }
  if (const auto pair = CoincidentNodes(t.coordinates)) {
    items[static_cast<std::size_t>(pair->second)].Fail(
        "node " + std::to_string(t.ids[pair->second]) + " is at the same place as node " +
        std::to_string(t.ids[pair->first]) + " (/nodes/" + std::to_string(pair->first) + ")");
  }
  return t;
}

int ParseDirection(const JsonNode& d, int dim) {
  const std::string s = d.String();
  for (int c = 0; c < dim && c < 3; ++c) {  // (dim is 2 or 3; the bound is for the reader)
    if (s == kDirectionNames[c]) return c;
  }
  d.Fail("unknown direction \"" + s + "\" (valid: " + (dim == 2 ? "x, y" : "x, y, z") + ")");
}

}  // namespace cb::io::reading
