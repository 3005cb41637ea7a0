#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "io/directions.h"
#include "io/fclib_file.h"
#include "io/gmsh.h"
#include "io/input_file.h"
#include "io/json_node.h"
#include "io/problem_file.h"
#include "io/problem_name.h"
#include "model/complementarity_model.h"
#include "model/obstacle.h"
#include "model/plane_stress_q4.h"
#include "model/rigid_motion.h"
#include "model/solid_hex8.h"
#include "model/truss.h"

namespace cb::io {

namespace {

// How the problem is loaded, as the file states it.
struct Loading {
  LoadingKind kind = LoadingKind::kFixedLoad;
  double load = 1.0;
  double arc_length = 0.1;
  int steps = 1;
};

Loading ReadLoading(const JsonNode& root) {
  Loading l;
  const JsonNode analysis = root.Field("analysis");
  const std::string kind = analysis.String();
  if (kind == "fixed-load") {
    l.kind = LoadingKind::kFixedLoad;
    if (auto load = root.Optional("load")) l.load = load->Number();
    for (const char* key : {"arc_length", "steps"}) {
      if (root.Has(key)) root.Field(key).Fail("only with \"analysis\": \"arc-length\"");
    }
  } else if (kind == "arc-length") {
    l.kind = LoadingKind::kArcLength;
    l.arc_length = root.Field("arc_length").Positive();
    l.steps = root.Field("steps").PositiveInt();
    if (root.Has("load")) root.Field("load").Fail("only with \"analysis\": \"fixed-load\"");
  } else {
    analysis.Fail("must be \"fixed-load\" or \"arc-length\", got \"" + kind + "\"");
  }
  return l;
}

// The run parameters `--set` may change, with the file's values as defaults.
Parameters RunParameters(double length_scale, double force_scale, const Loading& loading,
                         bool complementarity) {
  Parameters p;
  DeclareScaleParameters(length_scale, force_scale, &p);
  if (complementarity) return p;
  if (loading.kind == LoadingKind::kFixedLoad) {
    p.DeclareReal("load", loading.load, "lambda of the single fixed-load solve", -1e30, 1e30);
  } else {
    p.DeclareReal("arc_length", loading.arc_length, "theta of (33), ||(du, dlambda)||_2", 0.0, 1e30,
                  true);
    p.DeclareInteger("steps", loading.steps, "arc-length steps", 1, 2000000000);
  }
  return p;
}

void ApplySettings(const std::string& file, const std::map<std::string, std::string>& settings,
                   Parameters* p) {
  try {
    p->Apply(settings);
  } catch (const std::invalid_argument& e) {
    throw InputError(file, "", std::string("--set: ") + e.what());
  }
}

void ReadVersion(const JsonNode& root) {
  if (auto v = root.Optional("version")) {
    if (v->Integer() != 1) v->Fail("only version 1 is known, got " + std::to_string(v->Integer()));
  }
}

std::string OptionalString(const JsonNode& root, const char* key, const std::string& fallback) {
  auto v = root.Optional(key);
  return v ? v->String() : fallback;
}

// --- bodies -------------------------------------------------------------------------------

// Nodes by id: ids are any integers, unique; the body numbers nodes by position.
struct NodeTable {
  std::vector<std::int64_t> ids;
  std::map<std::int64_t, int> index;
  Mat coordinates;

  int Find(const JsonNode& ref) const {
    const std::int64_t id = ref.Integer();
    auto it = index.find(id);
    if (it == index.end()) ref.Fail("unknown node id " + std::to_string(id));
    return it->second;
  }
};

// A pair of nodes at the same place (within 1e-12 of the nodes' extent), or nothing: a node
// written twice leaves the elements on either copy unconnected, with no word from the model.
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

// The first element that has the same nodes as an earlier one, with that earlier one, or
// nothing: a hexahedron listed twice doubles its stiffness with no word from the model (and
// makes its faces interior, so a traction on them is refused for another reason).
template <typename Element>
std::optional<std::pair<std::size_t, std::size_t>> DuplicateElement(
    const std::vector<Element>& elements) {
  std::map<Element, std::size_t> first;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    Element sorted = elements[k];
    std::sort(sorted.begin(), sorted.end());
    const auto [it, added] = first.emplace(sorted, k);
    if (!added) return std::make_pair(it->second, k);
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

struct Obstacles {
  std::vector<std::shared_ptr<const Obstacle>> list;
  std::vector<std::string> ids;

  int Find(const JsonNode& ref) const {
    const std::string id = ref.String();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (ids[k] == id) return static_cast<int>(k);
    }
    std::string known;
    for (const auto& i : ids) known += (known.empty() ? "" : ", ") + i;
    ref.Fail("unknown obstacle \"" + id + "\" (defined: " + (known.empty() ? "none" : known) + ")");
  }
};

// A curved obstacle's "side": "solid" (default) or "cavity".
Ball::Side ReadSide(const JsonNode& item) {
  Ball::Side side = Ball::Side::kSolid;
  if (auto s = item.Optional("side")) {
    const std::string text = s->String();
    if (text == "cavity") {
      side = Ball::Side::kCavity;
    } else if (text != "solid") {
      s->Fail("must be \"solid\" or \"cavity\", got \"" + text + "\"");
    }
  }
  return side;
}

Obstacles ReadObstacles(const JsonNode& root, int dim) {
  Obstacles o;
  auto list = root.Optional("obstacles");
  if (!list) return o;
  for (const JsonNode& item : list->Items()) {
    const std::string type = item.Field("type").String();
    if (type == "half-space") {
      item.ExpectObject({"id", "type", "point", "normal"});
      const Point point = item.Field("point").Vector(dim);
      const Point normal = item.Field("normal").Vector(dim);
      if (!(normal.norm() > 0.0)) item.Field("normal").Fail("must not be the zero vector");
      o.list.push_back(std::make_shared<HalfSpace>(point, normal));
    } else if (type == "ball") {
      item.ExpectObject({"id", "type", "centre", "radius", "side"});
      const Point centre = item.Field("centre").Vector(dim);
      const double radius = item.Field("radius").Positive();
      o.list.push_back(std::make_shared<Ball>(centre, radius, ReadSide(item)));
    } else if (type == "cylinder" && dim == 3) {
      item.ExpectObject({"id", "type", "point", "axis", "radius", "side"});
      const Point point = item.Field("point").Vector(3);
      const Point axis = item.Field("axis").Vector(3);
      if (!(axis.norm() > 0.0)) item.Field("axis").Fail("must not be the zero vector");
      const double radius = item.Field("radius").Positive();
      o.list.push_back(std::make_shared<Cylinder>(point, axis, radius, ReadSide(item)));
    } else {
      item.Field("type").Fail(std::string("must be \"half-space\", \"ball\"") +
                              (dim == 3 ? " or \"cylinder\"" : "") + ", got \"" + type + "\"");
    }
    const JsonNode id = item.Field("id");
    const std::string text = id.String();
    if (text.empty()) id.Fail("must not be empty");
    if (std::find(o.ids.begin(), o.ids.end(), text) != o.ids.end()) {
      id.Fail("duplicate obstacle id \"" + text + "\"");
    }
    o.ids.push_back(text);
  }
  return o;
}

// Everything a body problem reads besides its body: the nodes, the mesh groups (Q4 from Gmsh),
// and where each pair came from (for messages about its gap).
class BodyInput {
 public:
  BodyInput(const JsonNode& root, int dim) : root_(root), dim_(dim) {}

  const JsonNode& root() const { return root_; }
  int dim() const { return dim_; }
  NodeTable nodes;
  std::optional<GmshMesh> mesh;
  std::string mesh_file;

  std::string NodeName(int index) const { return "node " + std::to_string(nodes.ids[index]); }

  const GmshMesh::Group& Group(const JsonNode& ref) const {
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
      ref.Fail(std::string(top == 1 ? "no 0-D or 1-D" : "no 0-D, 1-D or 2-D") +
               " physical group \"" + name + "\" in " + mesh_file +
               " (defined: " + (known.empty() ? "none" : known) + ")");
    }
    if (found->nodes.empty()) {
      ref.Fail("physical group \"" + name + "\" holds no " +
               (top == 1 ? "line or point" : "quadrangle, line or point") + " elements");
    }
    return *found;
  }

  // The nodes an entry names by "node": id or "group": name (exactly one of them).
  std::vector<int> SelectNodes(const JsonNode& entry) const {
    const bool by_node = entry.Has("node");
    if (by_node == entry.Has("group")) entry.Fail("give exactly one of \"node\" and \"group\"");
    if (by_node) return {nodes.Find(entry.Field("node"))};
    const JsonNode ref = entry.Field("group");
    std::vector<int> out;
    for (std::int64_t tag : Group(ref).nodes) out.push_back(nodes.index.at(tag));
    return out;
  }

  std::vector<bool> ReadSupports() const {
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

  // Nodal forces (one row per node); a force on a supported direction would be lost: refused.
  void AddLoads(const DofMap& dofs, Vec* load) const {
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

  std::vector<ContactPair> ReadPairs(const Obstacles& obstacles) {
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
  const std::string& PairWhere(int p) const { return pair_where_[p]; }

 private:
  JsonNode root_;
  int dim_;
  std::vector<std::string> pair_where_;
};

// A node on no member or element has no stiffness: the system would be singular.
void CheckConnected(const BodyInput& in, const std::vector<int>& uses, const char* what) {
  for (std::size_t n = 0; n < uses.size(); ++n) {
    if (uses[n] > 0) continue;
    const std::string reason =
        in.NodeName(static_cast<int>(n)) + " belongs to no " + what + " (a dangling node)";
    if (in.mesh) throw InputError(in.mesh_file, "", reason);
    in.root().Field("nodes").At(n).Fail(reason);
  }
}

// Rigid-body modes must be restrained: by the supports alone when there are no contact pairs,
// or by supports and contact normals together (model/rigid_motion.h).
void CheckHeld(const BodyInput& in, const ElasticBody& body,
               const std::vector<std::shared_ptr<const Obstacle>>& obstacles,
               const std::vector<ContactPair>& pairs) {
  const RigidMotionRestraint restraint = CheckRigidMotionRestraint(body, obstacles, pairs);
  const JsonNode where = in.root().Has("supports") ? in.root().Field("supports") : in.root();
  if (restraint.constraints == 0) {
    where.Fail(
        "no supports and no contact pairs: nothing holds the body (its stiffness is "
        "singular)");
  }
  if (restraint.free() <= 0) return;
  const std::string count =
      std::to_string(restraint.free()) + " rigid-body mode" + (restraint.free() > 1 ? "s" : "");
  const std::string& example = restraint.free_example;
  if (pairs.empty()) {
    where.Fail("the supports leave " + count + " free (e.g. " + example +
               ") and there are no contact pairs to hold the body: add supports");
  }
  where.Fail("neither the supports nor the contact pairs restrain " + count + " (e.g. " + example +
             "): the body can move freely");
}

// Pairs start with a non-negative gap; a node inside its obstacle usually means a normal that
// points the wrong way (it points INTO the obstacle).
void CheckInitialGaps(const BodyInput& in, const BodyContactModel& model,
                      const Obstacles& obstacles) {
  if (model.num_pairs() == 0) return;
  const ElasticBody& body = model.body();
  double extent = 0.0;
  for (int i = 0; i < body.num_nodes(); ++i) {
    extent = std::max(extent, body.reference(i).lpNorm<Eigen::Infinity>());
  }
  Vec phi;
  model.Gaps(Vec::Zero(model.num_dofs()), &phi);
  for (int p = 0; p < model.num_pairs(); ++p) {
    if (phi[p] > 1e-9 * std::max(extent, 1e-300)) {
      const ContactPair& pair = model.pairs()[p];
      throw InputError(in.root().file(), in.PairWhere(p),
                       in.NodeName(pair.node) + " starts inside obstacle \"" +
                           obstacles.ids[pair.obstacle] + "\" (penetration " + Describe(phi[p]) +
                           "); a half-space's normal points into the obstacle");
    }
  }
}

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

// The fields every body problem shares, after the body is built.
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

Problem ReadTruss(const JsonNode& root, const std::string& file,
                  const std::map<std::string, std::string>& settings) {
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

// The shortest side a Q4 element may have, relative to its longest.
constexpr double kDegenerateEdgeRatio = 1e-8;
// The isotropic "material": {"E": > 0, "nu": in (-1, 0.5)} of the continuum bodies.
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

// "mesh": {"file": F}, instead of inline "nodes" and "elements": F read relative to the
// problem file's directory.
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

// A Q4 element's corners must turn left at every corner: counter-clockwise and strictly convex
// (then the bilinear map's Jacobian is positive everywhere in the element).
std::string ElementProblem(const Mat& xy, const PlaneStressQ4::Element& e) {
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    const auto a = xy.row(e[k]);
    const auto b = xy.row(e[(k + 1) % 4]);
    area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
  }
  if (area < 0.0) {
    return "clockwise (signed area " + Describe(area) + "): list the nodes counter-clockwise";
  }
  if (!(area > 0.0)) return "zero area";
  // An edge far shorter than the element's longest is a degenerate element: its Jacobian is
  // positive in exact arithmetic but its stiffness is singular to working precision.
  double longest = 0.0, shortest = 0.0;
  int shortest_side = 0;
  for (int k = 0; k < 4; ++k) {
    const double length = (xy.row(e[(k + 1) % 4]) - xy.row(e[k])).norm();
    longest = std::max(longest, length);
    if (k == 0 || length < shortest) {
      shortest = length;
      shortest_side = k;
    }
  }
  if (!(shortest > kDegenerateEdgeRatio * longest)) {
    return "degenerate: its side " + std::to_string(shortest_side) + " has length " +
           Describe(shortest) + ", against " + Describe(longest) + " for its longest (below " +
           Describe(kDegenerateEdgeRatio) + " of it)";
  }
  for (int k = 0; k < 4; ++k) {
    const Eigen::RowVector2d in = xy.row(e[k]) - xy.row(e[(k + 3) % 4]);
    const Eigen::RowVector2d out = xy.row(e[(k + 1) % 4]) - xy.row(e[k]);
    const double turn = in[0] * out[1] - in[1] * out[0];
    if (!(turn > 1e-12 * in.norm() * out.norm())) {
      return "not strictly convex at its corner " + std::to_string(k) +
             " (a Q4 element's Jacobian must be positive everywhere)";
    }
  }
  return "";
}

Problem ReadPlaneStress(const JsonNode& root, const std::string& file, const std::string& directory,
                        const std::map<std::string, std::string>& settings) {
  root.ExpectObject({"kind",       "version",      "name",        "description",  "units",
                     "source",     "length_scale", "force_scale", "analysis",     "load",
                     "arc_length", "steps",        "control",     "deformation",  "thickness",
                     "material",   "nodes",        "elements",    "mesh",         "supports",
                     "loads",      "tractions",    "obstacles",   "contact_pairs"});
  if (auto d = root.Optional("deformation")) {
    if (d->String() != "small") {
      d->Fail("the plane-stress Q4 model is small-deformation only: must be \"small\", got \"" +
              d->String() + "\"");
    }
  }
  PlaneStressMaterial material;
  material.thickness = root.Field("thickness").Positive();
  ReadIsotropic(root, &material.youngs_modulus, &material.poisson_ratio);

  BodyInput in(root, 2);
  std::vector<PlaneStressQ4::Element> elements;
  std::vector<std::int64_t> element_tags;  // Gmsh tags, for element_sides
  if (root.Has("mesh")) {
    OpenMesh(root, directory, &in);
    const GmshMesh& g = *in.mesh;
    in.nodes.coordinates.resize(static_cast<Eigen::Index>(g.node_tags.size()), 2);
    for (std::size_t k = 0; k < g.node_tags.size(); ++k) {
      const auto row = static_cast<Eigen::Index>(k);
      if (g.coordinates(row, 2) != 0.0) {
        throw InputError(in.mesh_file, "node " + std::to_string(g.node_tags[k]),
                         "z = " + Describe(g.coordinates(row, 2)) +
                             ": a plane-stress mesh must lie in the plane z = 0");
      }
      in.nodes.coordinates.row(row) = g.coordinates.block(row, 0, 1, 2);
      in.nodes.index[g.node_tags[k]] = static_cast<int>(k);
      in.nodes.ids.push_back(g.node_tags[k]);
    }
    if (!g.hexes.empty()) {
      throw InputError(in.mesh_file, "", "a 3-D mesh of hexahedra: use \"kind\": \"solid-hex8\"");
    }
    if (const auto pair = CoincidentNodes(in.nodes.coordinates)) {
      throw InputError(in.mesh_file, "node " + std::to_string(in.nodes.ids[pair->second]),
                       "at the same place as node " + std::to_string(in.nodes.ids[pair->first]));
    }
    if (g.quads.empty()) {
      throw InputError(in.mesh_file, "", "no 4-node quadrangles (element type 3) in the mesh");
    }
    for (std::size_t k = 0; k < g.quads.size(); ++k) {
      PlaneStressQ4::Element e;
      for (int i = 0; i < 4; ++i) e[i] = in.nodes.index.at(g.quads[k][i]);
      const std::string why = ElementProblem(in.nodes.coordinates, e);
      if (!why.empty()) {
        throw InputError(in.mesh_file, "element " + std::to_string(g.quad_tags[k]),
                         why + (why[0] == 'c' ? " (Gmsh: reverse the surface's orientation)" : ""));
      }
      elements.push_back(e);
      element_tags.push_back(g.quad_tags[k]);
    }
  } else {
    in.nodes = ReadNodes(root.Field("nodes"), 2);
    const JsonNode list = root.Field("elements");
    if (list.Size() == 0) list.Fail("must list at least one element");
    for (const JsonNode& item : list.Items()) {
      item.ExpectObject({"nodes"});
      const JsonNode ids = item.Field("nodes");
      if (ids.Size() != 4) ids.Fail("a Q4 element has 4 nodes, got " + std::to_string(ids.Size()));
      PlaneStressQ4::Element e;
      for (int i = 0; i < 4; ++i) {
        e[i] = in.nodes.Find(ids.At(i));
        for (int j = 0; j < i; ++j) {
          if (e[j] == e[i]) ids.At(i).Fail(in.NodeName(e[i]) + " appears twice in the element");
        }
      }
      const std::string why = ElementProblem(in.nodes.coordinates, e);
      if (!why.empty()) ids.Fail(why);
      elements.push_back(e);
    }
  }
  std::vector<int> uses(in.nodes.ids.size(), 0);
  std::map<std::pair<int, int>, int> edge_count;  // element sides by their (sorted) end nodes
  for (const auto& e : elements) {
    for (int k = 0; k < 4; ++k) {
      ++uses[e[k]];
      ++edge_count[std::minmax(e[k], e[(k + 1) % 4])];
    }
  }
  CheckConnected(in, uses, "element");
  auto body =
      std::make_shared<PlaneStressQ4>(in.nodes.coordinates, elements, material, in.ReadSupports());

  // Edge tractions: each edge a boundary side of an element, the traction uniform on it.
  Vec load = Vec::Zero(body->num_dofs());
  if (auto list = root.Optional("tractions")) {
    for (const JsonNode& item : list->Items()) {
      item.ExpectObject({"edges", "element_sides", "group", "traction"});
      const int given = item.Has("edges") + item.Has("element_sides") + item.Has("group");
      if (given != 1) item.Fail("give exactly one of \"edges\", \"element_sides\" and \"group\"");
      const Point traction = item.Field("traction").Vector(2);
      auto apply = [&](int a, int b, const JsonNode& where) {
        const auto it = edge_count.find(std::minmax(a, b));
        if (it == edge_count.end()) {
          where.Fail(in.NodeName(a) + " - " + in.NodeName(b) + " is not a side of any element");
        }
        if (it->second > 1) {
          where.Fail(in.NodeName(a) + " - " + in.NodeName(b) +
                     " is an interior edge (shared by two elements); tractions act on the "
                     "boundary");
        }
        body->AddEdgeTraction(a, b, traction, &load);
      };
      if (auto edges = item.Optional("edges")) {
        for (const JsonNode& edge : edges->Items()) {
          if (edge.Size() != 2) edge.Fail("an edge is a pair of node ids");
          apply(in.nodes.Find(edge.At(0)), in.nodes.Find(edge.At(1)), edge);
        }
      } else if (auto sides = item.Optional("element_sides")) {
        for (const JsonNode& side : sides->Items()) {
          if (side.Size() != 2) side.Fail("an element side is [element, side 0..3]");
          const std::int64_t e = side.At(0).Integer();
          std::size_t index = elements.size();
          if (in.mesh) {
            const auto it = std::find(element_tags.begin(), element_tags.end(), e);
            index = static_cast<std::size_t>(it - element_tags.begin());
          } else if (e >= 0) {
            index = static_cast<std::size_t>(e);
          }
          if (index >= elements.size()) {
            side.At(0).Fail(in.mesh
                                ? "no quadrangle with Gmsh tag " + std::to_string(e)
                                : "no element " + std::to_string(e) + " (elements are " +
                                      "numbered 0.." + std::to_string(elements.size() - 1) + ")");
          }
          const std::int64_t s = side.At(1).Integer();
          if (s < 0 || s > 3) side.At(1).Fail("a side is 0..3, got " + std::to_string(s));
          const auto& el = elements[index];
          apply(el[s], el[(s + 1) % 4], side);
        }
      } else {
        const JsonNode ref = item.Field("group");
        const GmshMesh::Group& g = in.Group(ref);
        if (g.dim != 1) ref.Fail("tractions need a 1-D physical group (curves)");
        for (const auto& edge : g.edges) {
          apply(in.nodes.index.at(edge[0]), in.nodes.index.at(edge[1]), ref);
        }
      }
    }
  }
  Problem problem = FinishBody(in, body, load, file, settings);
  problem.description = OptionalString(
      root, "description",
      "plane-stress Q4 body, " + std::to_string(elements.size()) + " elements" +
          (in.mesh ? " (" + std::filesystem::path(in.mesh_file).filename().string() + ")" : ""));
  return problem;
}

// --- hexahedral solids --------------------------------------------------------------------

// The six faces of a hexahedron (VTK node order), each listed around its outward normal.
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

std::array<int, 4> SortedFace(std::array<int, 4> face) {
  std::sort(face.begin(), face.end());
  return face;
}

Problem ReadSolidHex8(const JsonNode& root, const std::string& file, const std::string& directory,
                      const std::map<std::string, std::string>& settings) {
  root.ExpectObject({"kind",       "version",      "name",         "description", "units",
                     "source",     "length_scale", "force_scale",  "analysis",    "load",
                     "arc_length", "steps",        "control",      "deformation", "material",
                     "nodes",      "elements",     "mesh",         "supports",    "loads",
                     "tractions",  "obstacles",    "contact_pairs"});
  SolidKinematics kinematics = SolidKinematics::kSmallStrain;
  if (auto d = root.Optional("deformation")) {
    if (d->String() == "large") {
      kinematics = SolidKinematics::kLargeStrain;
    } else if (d->String() != "small") {
      d->Fail("must be \"small\" or \"large\", got \"" + d->String() + "\"");
    }
  }
  SolidMaterial material;
  ReadIsotropic(root, &material.youngs_modulus, &material.poisson_ratio);

  BodyInput in(root, 3);
  std::vector<SolidHex8::Element> elements;
  const char* kOrder =
      "non-positive Jacobian: list the nodes 0-1-2-3 counter-clockwise (seen "
      "from the top face) below 4-5-6-7, node 4 + k above node k";
  if (root.Has("mesh")) {
    OpenMesh(root, directory, &in);
    const GmshMesh& g = *in.mesh;
    in.nodes.coordinates = g.coordinates;
    for (std::size_t k = 0; k < g.node_tags.size(); ++k) {
      in.nodes.index[g.node_tags[k]] = static_cast<int>(k);
      in.nodes.ids.push_back(g.node_tags[k]);
    }
    if (g.hexes.empty()) {
      throw InputError(in.mesh_file, "",
                       "no 8-node hexahedra (element type 5) in the mesh: make them with "
                       "transfinite, recombined volumes and write with gmsh -3 -format msh41");
    }
    if (const auto pair = CoincidentNodes(in.nodes.coordinates)) {
      throw InputError(in.mesh_file, "node " + std::to_string(in.nodes.ids[pair->second]),
                       "at the same place as node " + std::to_string(in.nodes.ids[pair->first]));
    }
    for (std::size_t k = 0; k < g.hexes.size(); ++k) {
      SolidHex8::Element e;
      for (int i = 0; i < 8; ++i) e[i] = in.nodes.index.at(g.hexes[k][i]);
      if (!SolidHex8::HasPositiveJacobian(in.nodes.coordinates, e)) {
        throw InputError(in.mesh_file, "element " + std::to_string(g.hex_tags[k]), kOrder);
      }
      elements.push_back(e);
    }
    if (const auto pair = DuplicateElement(elements)) {
      throw InputError(
          in.mesh_file, "element " + std::to_string(g.hex_tags[pair->second]),
          "the same eight nodes as element " + std::to_string(g.hex_tags[pair->first]));
    }
  } else {
    in.nodes = ReadNodes(root.Field("nodes"), 3);
    const JsonNode list = root.Field("elements");
    if (list.Size() == 0) list.Fail("must list at least one element");
    for (const JsonNode& item : list.Items()) {
      item.ExpectObject({"nodes"});
      const JsonNode ids = item.Field("nodes");
      if (ids.Size() != 8) {
        ids.Fail("a hexahedron has 8 nodes, got " + std::to_string(ids.Size()));
      }
      SolidHex8::Element e;
      for (int i = 0; i < 8; ++i) {
        e[i] = in.nodes.Find(ids.At(i));
        for (int j = 0; j < i; ++j) {
          if (e[j] == e[i]) ids.At(i).Fail(in.NodeName(e[i]) + " appears twice in the element");
        }
      }
      if (!SolidHex8::HasPositiveJacobian(in.nodes.coordinates, e)) ids.Fail(kOrder);
      elements.push_back(e);
    }
    if (const auto pair = DuplicateElement(elements)) {
      list.At(pair->second)
          .Field("nodes")
          .Fail("the same eight nodes as /elements/" + std::to_string(pair->first));
    }
  }
  std::vector<int> uses(in.nodes.ids.size(), 0);
  std::map<std::array<int, 4>, int> face_count;  // element faces by their sorted nodes
  for (const auto& e : elements) {
    for (int n : e) ++uses[n];
    for (const auto& f : kHexFaces) {
      ++face_count[SortedFace({e[f[0]], e[f[1]], e[f[2]], e[f[3]]})];
    }
  }
  CheckConnected(in, uses, "element");
  auto body = std::make_shared<SolidHex8>(in.nodes.coordinates, elements, material, kinematics,
                                          in.ReadSupports());

  // Face tractions: each face a boundary face of an element, the traction uniform on it.
  Vec load = Vec::Zero(body->num_dofs());
  if (auto list = root.Optional("tractions")) {
    for (const JsonNode& item : list->Items()) {
      item.ExpectObject({"faces", "group", "traction"});
      if (item.Has("faces") == item.Has("group")) {
        item.Fail("give exactly one of \"faces\" and \"group\"");
      }
      const Point traction = item.Field("traction").Vector(3);
      auto apply = [&](const SolidHex8::Face& face, const JsonNode& where) {
        const auto it = face_count.find(SortedFace(face));
        std::string name;
        for (int n : face) name += (name.empty() ? "" : ", ") + in.NodeName(n);
        if (it == face_count.end()) where.Fail("(" + name + ") is not a face of any element");
        if (it->second > 1) {
          where.Fail("(" + name +
                     ") is an interior face (shared by two elements); tractions act "
                     "on the boundary");
        }
        body->AddFaceTraction(face, traction, &load);
      };
      if (auto faces = item.Optional("faces")) {
        for (const JsonNode& face : faces->Items()) {
          if (face.Size() != 4) face.Fail("a face is 4 node ids, in order around it");
          SolidHex8::Face f;
          for (int i = 0; i < 4; ++i) f[i] = in.nodes.Find(face.At(i));
          apply(f, face);
        }
      } else {
        const JsonNode ref = item.Field("group");
        const GmshMesh::Group& g = in.Group(ref);
        if (g.dim != 2) ref.Fail("tractions need a 2-D physical group (surfaces)");
        for (const auto& face : g.faces) {
          SolidHex8::Face f;
          for (int i = 0; i < 4; ++i) f[i] = in.nodes.index.at(face[i]);
          apply(f, ref);
        }
      }
    }
  }
  Problem problem = FinishBody(in, body, load, file, settings);
  problem.description = OptionalString(
      root, "description",
      "hexahedral solid, " + std::to_string(elements.size()) + " elements" +
          (in.mesh ? " (" + std::filesystem::path(in.mesh_file).filename().string() + ")" : ""));
  return problem;
}

// --- complementarity ----------------------------------------------------------------------

Problem ReadLcp(const JsonNode& root, const std::string& file,
                const std::map<std::string, std::string>& settings) {
  root.ExpectObject({"kind", "version", "name", "description", "units", "source", "length_scale",
                     "force_scale", "analysis", "M", "q"});
  if (auto a = root.Optional("analysis")) {
    if (a->String() != "fixed-load") {
      a->Fail("an LCP is one fixed-load solve (lambda = 0): must be \"fixed-load\"");
    }
  }
  const JsonNode m = root.Field("M");
  std::vector<Triplet> entries;
  Eigen::Index n = 0;
  if (m.value().is_array()) {
    const auto rows = m.Items();
    n = static_cast<Eigen::Index>(rows.size());
    if (n == 0) m.Fail("must not be empty");
    for (Eigen::Index i = 0; i < n; ++i) {
      const JsonNode& row = rows[i];
      if (static_cast<Eigen::Index>(row.Size()) != n) {
        row.Fail("has " + std::to_string(row.Size()) + " entries, M has " + std::to_string(n) +
                 " rows: M must be square");
      }
      for (Eigen::Index j = 0; j < n; ++j) {
        const double v = row.At(j).Number();
        if (v != 0.0) entries.emplace_back(static_cast<int>(i), static_cast<int>(j), v);
      }
    }
  } else if (m.value().is_object()) {
    m.ExpectObject({"rows", "cols", "entries"});
    n = m.Field("rows").PositiveInt();
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
      entries.emplace_back(static_cast<int>(i), static_cast<int>(j), e.At(2).Number());
    }
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
  auto model = std::make_shared<ComplementarityModel>(ComplementarityModel::Lcp(matrix, q));
  double length = 1.0, force = 1.0;
  model->DataScales(&length, &force);  // the default: the sizes of z and w the data imply
  if (auto l = root.Optional("length_scale")) length = l->Positive();
  if (auto f = root.Optional("force_scale")) force = f->Positive();
  Parameters p = RunParameters(length, force, Loading{}, true);
  ApplySettings(file, settings, &p);

  Problem problem;
  problem.model = std::move(model);
  problem.scales = ScalesFrom(p);
  problem.parameters = p;
  problem.loading = LoadingKind::kFixedLoad;
  problem.load = 0.0;  // f = 0: (29) at lambda = 0 is w = M z + q = -r
  problem.steps = 1;
  problem.description = OptionalString(root, "description", "LCP, n = " + std::to_string(n));
  return problem;
}

}  // namespace

Problem ParseProblemFile(const std::string& text, const std::string& file,
                         const std::string& directory,
                         const std::map<std::string, std::string>& settings) {
  const Json json = ParseJson(text, file);
  const JsonNode root(&json, file, "");
  if (!json.is_object()) root.Fail("a problem file is a JSON object");
  ReadVersion(root);
  const JsonNode kind = root.Field("kind");
  const std::string k = kind.String();
  Problem problem;
  if (k == "truss") {
    problem = ReadTruss(root, file, settings);
  } else if (k == "plane-stress-q4") {
    problem = ReadPlaneStress(root, file, directory, settings);
  } else if (k == "solid-hex8") {
    problem = ReadSolidHex8(root, file, directory, settings);
  } else if (k == "lcp") {
    problem = ReadLcp(root, file, settings);
  } else {
    kind.Fail("must be \"truss\", \"plane-stress-q4\", \"solid-hex8\" or \"lcp\", got \"" + k +
              "\"");
  }
  problem.name = OptionalString(root, "name", std::filesystem::path(file).stem().string());
  if (problem.name.empty()) root.Field("name").Fail("must not be empty");
  if (!IsFileSafeName(problem.name)) {
    throw InputError(file, "/name",
                     "'" + problem.name +
                         "' cannot name the output files (vtk/NAME.pvd): use letters, digits "
                         "and ._+- only, not first '.' or '-'" +
                         (root.Has("name") ? "" : "; the default is the file's name"));
  }
  problem.units = OptionalString(root, "units", k == "lcp" ? "none" : "consistent units");
  return problem;
}

Problem LoadProblemFile(const std::string& path, const std::map<std::string, std::string>& settings,
                        std::uintmax_t max_bytes) {
  if (IsFclibPath(path)) return LoadFclibFile(path, settings);
  const std::string text = ReadInputFile(path, "problem file", max_bytes, "--allow-memory");
  const std::string directory = std::filesystem::path(path).parent_path().string();
  return ParseProblemFile(text, path, directory.empty() ? "." : directory, settings);
}

std::vector<std::string> ReferencedFiles(const std::string& text) {
  const auto root = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!root.is_object()) return {};
  const auto mesh = root.find("mesh");
  if (mesh == root.end() || !mesh->is_object()) return {};
  const auto file = mesh->find("file");
  if (file == mesh->end() || !file->is_string()) return {};
  return {file->get<std::string>()};
}

}  // namespace cb::io
