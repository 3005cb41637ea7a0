// "kind": "truss": pin-jointed members between nodes, in 2-D or 3-D (docs/problem-files.md).
#include <memory>

#include "io/problem_file_body.h"
#include "io/problem_file_checks.h"
#include "io/problem_file_kinds.h"
#include "io/problem_file_loading.h"
#include "model/truss.h"

namespace cb::io::reading {

Problem ReadTruss(const JsonNode& root, const std::string& file, const Settings& settings) {
  root.ExpectObject({"kind",       "version",      "name",        "description", "units",
                     "source",     "length_scale", "force_scale", "analysis",    "load",
                     "arc_length", "steps",        "control",     "dimension",   "nodes",
                     "members",    "supports",     "loads",       "obstacles",   "contact_pairs"});
  const JsonNode dimension = root.Field("dimension");
  const std::int64_t dim = dimension.Integer();
  if (dim != 2 && dim != 3) dimension.Fail("must be 2 or 3, got " + std::to_string(dim));
  BodyInput in(root, static_cast<int>(dim));
  in.nodes = ReadNodes(root.Field("nodes"), in.dim());

  const JsonNode members = root.Field("members");
  if (members.Size() == 0) members.Fail("must list at least one member");
  std::vector<TrussMember> list;
  std::vector<int> uses(in.nodes.ids.size(), 0);
  for (const JsonNode& item : members.Items()) {
    item.ExpectObject({"nodes", "E", "A"});
    const JsonNode ends = item.Field("nodes");
    if (ends.Size() != 2) ends.Fail("a member joins 2 nodes, got " + std::to_string(ends.Size()));
    const int i = in.nodes.Find(ends.At(0));
    const int j = in.nodes.Find(ends.At(1));
    if (i == j) ends.Fail("a member joins " + in.NodeName(i) + " to itself");
    const double length = (in.nodes.coordinates.row(j) - in.nodes.coordinates.row(i)).norm();
    if (!(length > 0.0)) {
      ends.Fail("zero-length member: " + in.NodeName(i) + " and " + in.NodeName(j) +
                " are at the same place");
    }
    list.push_back({i, j, item.Field("E").Positive(), item.Field("A").Positive()});
    ++uses[i];
    ++uses[j];
  }
  CheckConnected(in, uses, "member");
  auto body = std::make_shared<Truss>(in.nodes.coordinates, list, in.ReadSupports());
  Problem problem = FinishBody(in, body, Vec::Zero(body->num_dofs()), file, settings);
  problem.description =
      OptionalString(root, "description",
                     std::to_string(dim) + "-D truss, " + std::to_string(in.nodes.ids.size()) +
                         " nodes, " + std::to_string(list.size()) + " members");
  return problem;
}

}  // namespace cb::io::reading
