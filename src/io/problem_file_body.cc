#include "io/problem_file_body.h"

#include <filesystem>
#include <set>

#include "io/directions.h"
#include "io/problem_file_checks.h"
#include "io/problem_file_loading.h"
#include "model/plane_stress_q4.h"

namespace cb::io::reading {

const GmshMesh::Group& BodyInput::Group(const JsonNode& ref) const {
  if (!mesh) ref.Fail("groups name physical groups of a Gmsh mesh; this problem has no \"mesh\"");
  const std::string name = ref.String();
  const GmshMesh::Group* found = nullptr;
  // Groups of lower dimension than the body: points and curves (plane), also surfaces (3-D).
  const int top = dim_ - 1;
  for (const auto& g : mesh->groups) {
    if (g.name == name && g.dim <= top && (found == nullptr || g.dim > found->dim)) found = &g;
  }
  if (found == nullptr) {
    std::string known;
    for (const auto& g : mesh->groups) {
      if (g.dim <= top) known += (known.empty() ? "" : ", ") + g.name;
    }
    ref.Fail(std::string(top == 1 ? "no 0-D or 1-D" : "no 0-D, 1-D or 2-D") + " physical group \"" +
             name + "\" in " + mesh_file + " (defined: " + (known.empty() ? "none" : known) + ")");
  }
  if (found->nodes.empty()) {
    ref.Fail("physical group \"" + name + "\" holds no " +
             (top == 1 ? "line or point" : "quadrangle, line or point") + " elements");
  }
  return *found;
}

std::vector<int> BodyInput::SelectNodes(const JsonNode& entry) const {
  const bool by_node = entry.Has("node");
  if (by_node == entry.Has("group")) entry.Fail("give exactly one of \"node\" and \"group\"");
  if (by_node) return {nodes.Find(entry.Field("node"))};
  const JsonNode ref = entry.Field("group");
  std::vector<int> out;
  for (std::int64_t tag : Group(ref).nodes) out.push_back(nodes.index.at(tag));
  return out;
}

std::vector<bool> BodyInput::ReadSupports() const {
  std::vector<bool> fixed(nodes.ids.size() * static_cast<std::size_t>(dim_), false);
  auto list = root_.Optional("supports");
  if (!list) return fixed;
  for (const JsonNode& item : list->Items()) {
    item.ExpectObject({"node", "group", "fixed"});
    const std::vector<int> selected = SelectNodes(item);
    const JsonNode directions = item.Field("fixed");
    if (directions.Size() == 0) directions.Fail("must name at least one direction");
    for (const JsonNode& d : directions.Items()) {
      const int c = ParseDirection(d, dim_);
      for (int n : selected) fixed[static_cast<std::size_t>(n) * dim_ + c] = true;
    }
  }
  return fixed;
}

void BodyInput::AddLoads(const DofMap& dofs, Vec* load) const {
  auto list = root_.Optional("loads");
  if (!list) return;
  for (const JsonNode& item : list->Items()) {
    item.ExpectObject({"node", "group", "force"});
    const std::vector<int> selected = SelectNodes(item);
    const JsonNode force_node = item.Field("force");
    const Point force = force_node.Vector(dim_);
    for (int n : selected) {
      for (int c = 0; c < dim_; ++c) {
        if (force[c] != 0.0 && dofs.dof(n, c) < 0) {
          force_node.Fail("a force in " + std::string(kDirectionNames[c]) + " on " + NodeName(n) +
                          ", which is supported in " + kDirectionNames[c] + ", would be lost");
        }
      }
      AddNodalForce(dofs, n, force, load);
    }
  }
}

std::vector<ContactPair> BodyInput::ReadPairs(const Obstacles& obstacles) {
  std::vector<ContactPair> pairs;
  auto list = root_.Optional("contact_pairs");
  if (!list) return pairs;
  std::set<std::pair<int, int>> seen;
  for (const JsonNode& item : list->Items()) {
    item.ExpectObject({"node", "group", "obstacle"});
    const int obstacle = obstacles.Find(item.Field("obstacle"));
    for (int n : SelectNodes(item)) {
      if (!seen.insert({n, obstacle}).second) {
        item.Fail(NodeName(n) + " is paired with obstacle \"" + obstacles.ids[obstacle] +
                  "\" twice");
      }
      pairs.push_back({n, obstacle});
      pair_where_.push_back(item.where());
    }
  }
  return pairs;
}

namespace {

void ReadControl(const BodyInput& in, const DofMap& dofs, Problem* problem) {
  auto control = in.root().Optional("control");
  if (!control) return;
  control->ExpectObject({"node", "direction", "label"});
  const int node = in.nodes.Find(control->Field("node"));
  const int c = ParseDirection(control->Field("direction"), in.dim());
  problem->control_dof = dofs.dof(node, c);
  if (problem->control_dof < 0) {
    control->Field("direction")
        .Fail(std::string("direction ") + kDirectionNames[c] + " of " + in.NodeName(node) +
              " is supported: there is no displacement to record");
  }
  problem->control_label = OptionalString(
      *control, "label", std::string(kDirectionNames[c]) + "-displacement of " + in.NodeName(node));
}

}  // namespace

std::string BodyInput::MeshNote() const {
  return mesh ? " (" + std::filesystem::path(mesh_file).filename().string() + ")" : "";
}

Problem FinishBody(BodyInput& in, const std::shared_ptr<const ElasticBody>& body,
                   const Vec& nodal_load, const std::string& file,
                   const std::map<std::string, std::string>& settings) {
  const JsonNode& root = in.root();
  const Obstacles obstacles = ReadObstacles(root, in.dim());
  const std::vector<ContactPair> pairs = in.ReadPairs(obstacles);
  CheckHeld(in, *body, obstacles.list, pairs);
  Vec load = nodal_load;
  in.AddLoads(body->dofs(), &load);
  const Loading loading = ReadLoading(root);
  Parameters p = RunParameters(root.Field("length_scale").Positive(),
                               root.Field("force_scale").Positive(), loading, false);
  ApplySettings(file, settings, &p);
  Problem problem = MakeBodyProblem(body, obstacles.list, pairs, load, p);
  CheckInitialGaps(in, *problem.body, obstacles);
  problem.loading = loading.kind;
  if (loading.kind == LoadingKind::kFixedLoad) {
    problem.load = p.Real("load");
    problem.steps = 1;
  } else {
    problem.arc_length = p.Real("arc_length");
    problem.steps = p.Integer("steps");
  }
  ReadControl(in, body->dofs(), &problem);
  problem.node_ids = in.nodes.ids;
  problem.obstacle_ids = obstacles.ids;
  return problem;
}

void ReadIsotropic(const JsonNode& root, double* youngs_modulus, double* poisson_ratio) {
  const JsonNode mat = root.Field("material");
  mat.ExpectObject({"E", "nu"});
  *youngs_modulus = mat.Field("E").Positive();
  const JsonNode nu = mat.Field("nu");
  *poisson_ratio = nu.Number();
  if (!(*poisson_ratio > -1.0 && *poisson_ratio < 0.5)) {
    nu.Fail("must be in (-1, 0.5), got " + Describe(*poisson_ratio));
  }
}

void OpenMesh(const JsonNode& root, const std::string& directory, BodyInput* in) {
  for (const char* key : {"nodes", "elements"}) {
    if (root.Has(key)) root.Field(key).Fail("give either \"mesh\" or \"nodes\" and \"elements\"");
  }
  const JsonNode mesh = root.Field("mesh");
  mesh.ExpectObject({"file"});
  const std::filesystem::path relative = mesh.Field("file").String();
  in->mesh_file = (std::filesystem::path(directory) / relative).lexically_normal().string();
  in->mesh = ReadGmsh(in->mesh_file);
}

}  // namespace cb::io::reading
