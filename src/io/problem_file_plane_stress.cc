// "kind": "plane-stress-q4": a small-deformation plane-stress body of Q4 elements, inline or
// from a Gmsh mesh, with edge tractions (docs/problem-files.md).
#include <algorithm>
#include <map>
#include <memory>

#include "io/problem_file_body.h"
#include "io/problem_file_checks.h"
#include "io/problem_file_kinds.h"
#include "io/problem_file_loading.h"
#include "model/plane_stress_q4.h"

namespace cb::io::reading {

namespace {

// The shortest side a Q4 element may have, relative to its longest.
constexpr double kDegenerateEdgeRatio = 1e-8;
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

// The elements, with their Gmsh tags (for "element_sides") when they come from a mesh.
struct Q4Elements {
  std::vector<PlaneStressQ4::Element> list;
  std::vector<std::int64_t> tags;
};

PlaneStressMaterial ReadPlaneStressMaterial(const JsonNode& root) {
  if (auto d = root.Optional("deformation")) {
    if (d->String() != "small") {
      d->Fail("the plane-stress Q4 model is small-deformation only: must be \"small\", got \"" +
              d->String() + "\"");
    }
  }
  PlaneStressMaterial material;
  material.thickness = root.Field("thickness").Positive();
  ReadIsotropic(root, &material.youngs_modulus, &material.poisson_ratio);
  return material;
}

// The mesh's nodes, which must lie in the plane z = 0, as the node table.
void TakePlaneNodes(BodyInput* in) {
  const GmshMesh& g = *in->mesh;
  in->nodes.coordinates.resize(static_cast<Eigen::Index>(g.node_tags.size()), 2);
  for (std::size_t k = 0; k < g.node_tags.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    if (g.coordinates(row, 2) != 0.0) {
      throw InputError(in->mesh_file, "node " + std::to_string(g.node_tags[k]),
                       "z = " + Describe(g.coordinates(row, 2)) +
                           ": a plane-stress mesh must lie in the plane z = 0");
    }
    in->nodes.coordinates.row(row) = g.coordinates.block(row, 0, 1, 2);
    in->nodes.index[g.node_tags[k]] = static_cast<int>(k);
    in->nodes.ids.push_back(g.node_tags[k]);
  }
}

// "mesh": the nodes and the quadrangles of a Gmsh file.
Q4Elements ReadMeshElements(const JsonNode& root, const std::string& directory, BodyInput* in) {
  OpenMesh(root, directory, in);
  TakePlaneNodes(in);
  const GmshMesh& g = *in->mesh;
  if (!g.hexes.empty()) {
    throw InputError(in->mesh_file, "", "a 3-D mesh of hexahedra: use \"kind\": \"solid-hex8\"");
  }
  if (const auto pair = CoincidentNodes(in->nodes.coordinates)) {
    throw InputError(in->mesh_file, "node " + std::to_string(in->nodes.ids[pair->second]),
                     "at the same place as node " + std::to_string(in->nodes.ids[pair->first]));
  }
  if (g.quads.empty()) {
    throw InputError(in->mesh_file, "", "no 4-node quadrangles (element type 3) in the mesh");
  }
  Q4Elements elements;
  for (std::size_t k = 0; k < g.quads.size(); ++k) {
    PlaneStressQ4::Element e;
    for (int i = 0; i < 4; ++i) e[i] = in->nodes.index.at(g.quads[k][i]);
    const std::string why = ElementProblem(in->nodes.coordinates, e);
    if (!why.empty()) {
      throw InputError(in->mesh_file, "element " + std::to_string(g.quad_tags[k]),
                       why + (why[0] == 'c' ? " (Gmsh: reverse the surface's orientation)" : ""));
    }
    elements.list.push_back(e);
    elements.tags.push_back(g.quad_tags[k]);
  }
  return elements;
}

// Inline "nodes" and "elements".
Q4Elements ReadInlineElements(const JsonNode& root, BodyInput* in) {
  in->nodes = ReadNodes(root.Field("nodes"), 2);
  const JsonNode list = root.Field("elements");
  if (list.Size() == 0) list.Fail("must list at least one element");
  Q4Elements elements;
  for (const JsonNode& item : list.Items()) {
    item.ExpectObject({"nodes"});
    const JsonNode ids = item.Field("nodes");
    if (ids.Size() != 4) ids.Fail("a Q4 element has 4 nodes, got " + std::to_string(ids.Size()));
    PlaneStressQ4::Element e;
    for (int i = 0; i < 4; ++i) {
      e[i] = in->nodes.Find(ids.At(i));
      for (int j = 0; j < i; ++j) {
        if (e[j] == e[i]) ids.At(i).Fail(in->NodeName(e[i]) + " appears twice in the element");
      }
    }
    const std::string why = ElementProblem(in->nodes.coordinates, e);
    if (!why.empty()) ids.Fail(why);
    elements.list.push_back(e);
  }
  return elements;
}

// Every node on an element (else refused), and the element sides by their (sorted) end nodes,
// each with the number of elements it is a side of.
std::map<std::pair<int, int>, int> CountSides(const BodyInput& in, const Q4Elements& elements) {
  std::vector<int> uses(in.nodes.ids.size(), 0);
  std::map<std::pair<int, int>, int> edge_count;
  for (const auto& e : elements.list) {
    for (int k = 0; k < 4; ++k) {
      ++uses[e[k]];
      ++edge_count[std::minmax(e[k], e[(k + 1) % 4])];
    }
  }
  CheckConnected(in, uses, "element");
  return edge_count;
}

// Edge tractions: each edge a boundary side of an element, the traction uniform on it.
class EdgeTractions {
 public:
  EdgeTractions(const BodyInput& in, const Q4Elements& elements,
                const std::map<std::pair<int, int>, int>& edge_count, const PlaneStressQ4& body,
                Vec* load)
      : in_(in), elements_(elements), edge_count_(edge_count), body_(body), load_(load) {}

  void Read(const JsonNode& item) {
    item.ExpectObject({"edges", "element_sides", "group", "traction"});
    const int given = item.Has("edges") + item.Has("element_sides") + item.Has("group");
    if (given != 1) item.Fail("give exactly one of \"edges\", \"element_sides\" and \"group\"");
    const Point traction = item.Field("traction").Vector(2);
    if (auto edges = item.Optional("edges")) {
      for (const JsonNode& edge : edges->Items()) {
        if (edge.Size() != 2) edge.Fail("an edge is a pair of node ids");
        Apply(in_.nodes.Find(edge.At(0)), in_.nodes.Find(edge.At(1)), traction, edge);
      }
    } else if (auto sides = item.Optional("element_sides")) {
      for (const JsonNode& side : sides->Items()) ApplyElementSide(side, traction);
    } else {
      const JsonNode ref = item.Field("group");
      const GmshMesh::Group& g = in_.Group(ref);
      if (g.dim != 1) ref.Fail("tractions need a 1-D physical group (curves)");
      for (const auto& edge : g.edges) {
        Apply(in_.nodes.index.at(edge[0]), in_.nodes.index.at(edge[1]), traction, ref);
      }
    }
  }

 private:
  void Apply(int a, int b, const Point& traction, const JsonNode& where) {
    const auto it = edge_count_.find(std::minmax(a, b));
    if (it == edge_count_.end()) {
      where.Fail(in_.NodeName(a) + " - " + in_.NodeName(b) + " is not a side of any element");
    }
    if (it->second > 1) {
      where.Fail(in_.NodeName(a) + " - " + in_.NodeName(b) +
                 " is an interior edge (shared by two elements); tractions act on the "
                 "boundary");
    }
    body_.AddEdgeTraction(a, b, traction, load_);
  }

  // [element, side 0..3]: the element by its Gmsh tag (a mesh) or its position (inline).
  void ApplyElementSide(const JsonNode& side, const Point& traction) {
    const auto& elements = elements_.list;
    if (side.Size() != 2) side.Fail("an element side is [element, side 0..3]");
    const std::int64_t e = side.At(0).Integer();
    std::size_t index = elements.size();
    if (in_.mesh) {
      const auto it = std::find(elements_.tags.begin(), elements_.tags.end(), e);
      index = static_cast<std::size_t>(it - elements_.tags.begin());
    } else if (e >= 0) {
      index = static_cast<std::size_t>(e);
    }
    if (index >= elements.size()) {
      side.At(0).Fail(in_.mesh ? "no quadrangle with Gmsh tag " + std::to_string(e)
                               : "no element " + std::to_string(e) + " (elements are " +
                                     "numbered 0.." + std::to_string(elements.size() - 1) + ")");
    }
    const std::int64_t s = side.At(1).Integer();
    if (s < 0 || s > 3) side.At(1).Fail("a side is 0..3, got " + std::to_string(s));
    const auto& el = elements[index];
    Apply(el[s], el[(s + 1) % 4], traction, side);
  }

  const BodyInput& in_;
  const Q4Elements& elements_;
  const std::map<std::pair<int, int>, int>& edge_count_;
  const PlaneStressQ4& body_;
  Vec* load_;
};

}  // namespace

Problem ReadPlaneStress(const JsonNode& root, const std::string& file, const std::string& directory,
                        const Settings& settings) {
  root.ExpectObject({"kind",       "version",      "name",        "description",  "units",
                     "source",     "length_scale", "force_scale", "analysis",     "load",
                     "arc_length", "steps",        "control",     "deformation",  "thickness",
                     "material",   "nodes",        "elements",    "mesh",         "supports",
                     "loads",      "tractions",    "obstacles",   "contact_pairs"});
  const PlaneStressMaterial material = ReadPlaneStressMaterial(root);
  BodyInput in(root, 2);
  const Q4Elements elements =
      root.Has("mesh") ? ReadMeshElements(root, directory, &in) : ReadInlineElements(root, &in);
  const std::map<std::pair<int, int>, int> edge_count = CountSides(in, elements);
  auto body = std::make_shared<PlaneStressQ4>(in.nodes.coordinates, elements.list, material,
                                              in.ReadSupports());
  Vec load = Vec::Zero(body->num_dofs());
  if (auto list = root.Optional("tractions")) {
    EdgeTractions tractions(in, elements, edge_count, *body, &load);
    for (const JsonNode& item : list->Items()) tractions.Read(item);
  }
  Problem problem = FinishBody(in, body, load, file, settings);
  problem.description =
      OptionalString(root, "description",
                     "plane-stress Q4 body, " + std::to_string(elements.list.size()) + " elements" +
                         in.MeshNote());
  return problem;
}

}  // namespace cb::io::reading
