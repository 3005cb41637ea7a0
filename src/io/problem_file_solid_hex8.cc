// "kind": "solid-hex8": a solid of eight-node hexahedra, small- or large-strain, inline or from
// a Gmsh mesh, with face tractions (docs/problem-files.md).
#include <algorithm>
#include <array>
#include <map>
#include <memory>

#include "io/problem_file_body.h"
#include "io/problem_file_checks.h"
#include "io/problem_file_kinds.h"
#include "io/problem_file_loading.h"
#include "model/solid_hex8.h"

namespace cb::io::reading {

namespace {

// The six faces of a hexahedron (VTK node order), each listed around its outward normal.
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

constexpr const char* kOrder =
    "non-positive Jacobian: list the nodes 0-1-2-3 counter-clockwise (seen "
    "from the top face) below 4-5-6-7, node 4 + k above node k";

using FaceCount = std::map<std::array<int, 4>, int>;  // element faces by their sorted nodes

std::array<int, 4> SortedFace(std::array<int, 4> face) {
  std::sort(face.begin(), face.end());
  return face;
}

SolidKinematics ReadKinematics(const JsonNode& root) {
  SolidKinematics kinematics = SolidKinematics::kSmallStrain;
  if (auto d = root.Optional("deformation")) {
    if (d->String() == "large") {
      kinematics = SolidKinematics::kLargeStrain;
    } else if (d->String() != "small") {
      d->Fail("must be \"small\" or \"large\", got \"" + d->String() + "\"");
    }
  }
  return kinematics;
}

// "mesh": the nodes and the hexahedra of a Gmsh file.
std::vector<SolidHex8::Element> ReadMeshElements(const JsonNode& root, const std::string& directory,
                                                 BodyInput* in) {
  OpenMesh(root, directory, in);
  const GmshMesh& g = *in->mesh;
  in->nodes.coordinates = g.coordinates;
  for (std::size_t k = 0; k < g.node_tags.size(); ++k) {
    in->nodes.index[g.node_tags[k]] = static_cast<int>(k);
    in->nodes.ids.push_back(g.node_tags[k]);
  }
  if (g.hexes.empty()) {
    throw InputError(in->mesh_file, "",
                     "no 8-node hexahedra (element type 5) in the mesh: make them with "
                     "transfinite, recombined volumes and write with gmsh -3 -format msh41");
  }
  if (const auto pair = CoincidentNodes(in->nodes.coordinates)) {
    throw InputError(in->mesh_file, "node " + std::to_string(in->nodes.ids[pair->second]),
                     "at the same place as node " + std::to_string(in->nodes.ids[pair->first]));
  }
  std::vector<SolidHex8::Element> elements;
  for (std::size_t k = 0; k < g.hexes.size(); ++k) {
    SolidHex8::Element e;
    for (int i = 0; i < 8; ++i) e[i] = in->nodes.index.at(g.hexes[k][i]);
    if (!SolidHex8::HasPositiveJacobian(in->nodes.coordinates, e)) {
      throw InputError(in->mesh_file, "element " + std::to_string(g.hex_tags[k]), kOrder);
    }
    elements.push_back(e);
  }
  if (const auto pair = DuplicateElement(elements)) {
    throw InputError(in->mesh_file, "element " + std::to_string(g.hex_tags[pair->second]),
                     "the same eight nodes as element " + std::to_string(g.hex_tags[pair->first]));
  }
  return elements;
}

// Inline "nodes" and "elements".
std::vector<SolidHex8::Element> ReadInlineElements(const JsonNode& root, BodyInput* in) {
  in->nodes = ReadNodes(root.Field("nodes"), 3);
  const JsonNode list = root.Field("elements");
  if (list.Size() == 0) list.Fail("must list at least one element");
  std::vector<SolidHex8::Element> elements;
  for (const JsonNode& item : list.Items()) {
    item.ExpectObject({"nodes"});
    const JsonNode ids = item.Field("nodes");
    if (ids.Size() != 8) {
      ids.Fail("a hexahedron has 8 nodes, got " + std::to_string(ids.Size()));
    }
    SolidHex8::Element e;
    for (int i = 0; i < 8; ++i) {
      e[i] = in->nodes.Find(ids.At(i));
      for (int j = 0; j < i; ++j) {
        if (e[j] == e[i]) ids.At(i).Fail(in->NodeName(e[i]) + " appears twice in the element");
      }
    }
    if (!SolidHex8::HasPositiveJacobian(in->nodes.coordinates, e)) ids.Fail(kOrder);
    elements.push_back(e);
  }
  if (const auto pair = DuplicateElement(elements)) {
    list.At(pair->second)
        .Field("nodes")
        .Fail("the same eight nodes as /elements/" + std::to_string(pair->first));
  }
  return elements;
}

// Every node on an element (else refused), and the element faces by their sorted nodes, each
// with the number of elements it is a face of.
FaceCount CountFaces(const BodyInput& in, const std::vector<SolidHex8::Element>& elements) {
  std::vector<int> uses(in.nodes.ids.size(), 0);
  FaceCount face_count;
  for (const auto& e : elements) {
    for (int n : e) ++uses[n];
    for (const auto& f : kHexFaces) {
      ++face_count[SortedFace({e[f[0]], e[f[1]], e[f[2]], e[f[3]]})];
    }
  }
  CheckConnected(in, uses, "element");
  return face_count;
}

// A uniform traction on a face, which must be a boundary face of an element.
void ApplyFaceTraction(const BodyInput& in, const FaceCount& face_count, const SolidHex8& body,
                       const SolidHex8::Face& face, const Point& traction, const JsonNode& where,
                       Vec* load) {
  const auto it = face_count.find(SortedFace(face));
  std::string name;
  for (int n : face) name += (name.empty() ? "" : ", ") + in.NodeName(n);
  if (it == face_count.end()) where.Fail("(" + name + ") is not a face of any element");
  if (it->second > 1) {
    where.Fail("(" + name +
               ") is an interior face (shared by two elements); tractions act "
               "on the boundary");
  }
  body.AddFaceTraction(face, traction, load);
}

// One entry of "tractions": its faces by their node ids, or a 2-D physical group.
void ReadFaceTraction(const JsonNode& item, const BodyInput& in, const FaceCount& face_count,
                      const SolidHex8& body, Vec* load) {
  item.ExpectObject({"faces", "group", "traction"});
  if (item.Has("faces") == item.Has("group")) {
    item.Fail("give exactly one of \"faces\" and \"group\"");
  }
  const Point traction = item.Field("traction").Vector(3);
  if (auto faces = item.Optional("faces")) {
    for (const JsonNode& face : faces->Items()) {
      if (face.Size() != 4) face.Fail("a face is 4 node ids, in order around it");
      SolidHex8::Face f;
      for (int i = 0; i < 4; ++i) f[i] = in.nodes.Find(face.At(i));
      ApplyFaceTraction(in, face_count, body, f, traction, face, load);
    }
  } else {
    const JsonNode ref = item.Field("group");
    const GmshMesh::Group& g = in.Group(ref);
    if (g.dim != 2) ref.Fail("tractions need a 2-D physical group (surfaces)");
    for (const auto& face : g.faces) {
      SolidHex8::Face f;
      for (int i = 0; i < 4; ++i) f[i] = in.nodes.index.at(face[i]);
      ApplyFaceTraction(in, face_count, body, f, traction, ref, load);
    }
  }
}

}  // namespace

Problem ReadSolidHex8(const JsonNode& root, const std::string& file, const std::string& directory,
                      const Settings& settings) {
  root.ExpectObject({"kind",       "version",      "name",         "description", "units",
                     "source",     "length_scale", "force_scale",  "analysis",    "load",
                     "arc_length", "steps",        "control",      "deformation", "material",
                     "nodes",      "elements",     "mesh",         "supports",    "loads",
                     "tractions",  "obstacles",    "contact_pairs"});
  const SolidKinematics kinematics = ReadKinematics(root);
  SolidMaterial material;
  ReadIsotropic(root, &material.youngs_modulus, &material.poisson_ratio);
  BodyInput in(root, 3);
  const std::vector<SolidHex8::Element> elements =
      root.Has("mesh") ? ReadMeshElements(root, directory, &in) : ReadInlineElements(root, &in);
  const FaceCount face_count = CountFaces(in, elements);
  auto body = std::make_shared<SolidHex8>(in.nodes.coordinates, elements, material, kinematics,
                                          in.ReadSupports());
  Vec load = Vec::Zero(body->num_dofs());
  if (auto list = root.Optional("tractions")) {
    for (const JsonNode& item : list->Items()) {
      ReadFaceTraction(item, in, face_count, *body, &load);
    }
  }
  Problem problem = FinishBody(in, body, load, file, settings);
  problem.description = OptionalString(
      root, "description",
      "hexahedral solid, " + std::to_string(elements.size()) + " elements" + in.MeshNote());
  return problem;
}

}  // namespace cb::io::reading
