#include "io/gmsh.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "io/input_error.h"
#include "io/input_file.h"

namespace cb::io {

namespace {

struct Token {
  std::string text;
  int line = 0;
};

// Whitespace-separated tokens with their line numbers; a double-quoted string (a physical
// name may hold spaces) is one token without its quotes.
std::vector<Token> Tokenize(const std::string& text, const std::string& file) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == '"') {
      const std::size_t close = text.find('"', i + 1);
      if (close == std::string::npos || text.find('\n', i) < close) {
        throw InputError(file, "line " + std::to_string(line), "unterminated quoted name");
      }
      tokens.push_back({text.substr(i + 1, close - i - 1), line});
      i = close + 1;
    } else {
      std::size_t j = i;
      while (j < text.size() && text[j] != ' ' && text[j] != '\t' && text[j] != '\r' &&
             text[j] != '\n') {
        ++j;
      }
      tokens.push_back({text.substr(i, j - i), line});
      i = j;
    }
  }
  return tokens;
}

class Cursor {
 public:
  Cursor(std::vector<Token> tokens, std::string file)
      : tokens_(std::move(tokens)), file_(std::move(file)) {}

  bool done() const { return next_ >= tokens_.size(); }
  int line() const {
    if (tokens_.empty()) return 1;
    return tokens_[std::min(next_, tokens_.size() - 1)].line;
  }
  [[noreturn]] void Fail(const std::string& reason) const {
    throw InputError(file_, "line " + std::to_string(line()), reason);
  }
  const Token& Next(const char* what) {
    if (done()) Fail(std::string("unexpected end of file, expected ") + what);
    return tokens_[next_++];
  }
  const std::string& Peek() const { return tokens_[next_].text; }
  std::int64_t Int(const char* what) {
    const Token& t = Next(what);
    std::int64_t v = 0;
    auto [end, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (ec != std::errc() || end != t.text.data() + t.text.size()) {
      --next_;
      Fail(std::string("expected ") + what + " (an integer), got '" + t.text + "'");
    }
    return v;
  }
  std::int64_t Count(const char* what) {
    const std::int64_t v = Int(what);
    if (v < 0 || v > 100000000) {
      --next_;
      Fail(std::string(what) + " out of range: " + std::to_string(v));
    }
    return v;
  }
  double Real(const char* what) {
    const Token& t = Next(what);
    double v = 0.0;
    auto [end, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (ec != std::errc() || end != t.text.data() + t.text.size() || !std::isfinite(v)) {
      --next_;
      Fail(std::string("expected ") + what + " (a finite number), got '" + t.text + "'");
    }
    return v;
  }
  void Expect(const std::string& word) {
    const Token& t = Next(word.c_str());
    if (t.text != word) {
      --next_;
      Fail("expected " + word + ", got '" + t.text + "'");
    }
  }

 private:
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  std::string file_;
};

const char* ElementName(std::int64_t type) {
  switch (type) {
    case 1:
      return "2-node line";
    case 2:
      return "3-node triangle";
    case 3:
      return "4-node quadrangle";
    case 4:
      return "4-node tetrahedron";
    case 5:
      return "8-node hexahedron";
    case 6:
      return "6-node prism";
    case 7:
      return "5-node pyramid";
    case 8:
      return "3-node line";
    case 9:
      return "6-node triangle";
    case 10:
      return "9-node quadrangle";
    case 15:
      return "1-node point";
    case 16:
      return "8-node quadrangle";
    default:
      return "element";
  }
}

int NodesOf(std::int64_t type) {
  switch (type) {
    case 1:
      return 2;
    case 3:
      return 4;
    case 5:
      return 8;
    case 15:
      return 1;
    default:
      return 0;
  }
}

}  // namespace

GmshMesh ReadGmsh(const std::string& path) {
  return ParseGmsh(ReadInputFile(path, "mesh file"), path);
}

namespace {

// The header decides before anything else is read: a binary file's body is not text.
void CheckHeader(const std::string& text, const std::string& file) {
  std::istringstream head(text);
  std::string first, version, type;
  head >> first >> version >> type;
  if (first != "$MeshFormat") {
    throw InputError(file, "line 1", "not a Gmsh mesh file (expected $MeshFormat)");
  }
  if (version != "4.1") {
    throw InputError(file, "line 2",
                     "Gmsh mesh format version '" + version +
                         "' is not supported: only 4.1 ASCII is read (save with "
                         "Mesh.MshFileVersion = 4.1, or gmsh -format msh41)");
  }
  if (type != "0") {
    throw InputError(file, "line 2",
                     "binary Gmsh files are not supported: save as ASCII (Mesh.Binary = 0)");
  }
}

// What the sections leave for the end: the physical names and which entities carry them, and
// the line, point and face elements by their entity, resolved to groups once all is read.
struct GmshReading {
  GmshMesh mesh;
  std::map<std::pair<int, int>, std::string> names;          // (dim, physical tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> physical;  // (dim, entity) -> physical tags
  std::map<std::int64_t, int> node_index;
  bool have_entities = false, have_nodes = false, have_elements = false;
  std::map<std::pair<int, int>, std::vector<std::array<std::int64_t, 2>>> entity_edges;
  std::map<std::pair<int, int>, std::vector<std::int64_t>> entity_nodes;
  std::map<std::pair<int, int>, std::vector<std::array<std::int64_t, 4>>> entity_faces;
};

void ReadPhysicalNames(Cursor& c, GmshReading* r) {
  const std::int64_t n = c.Count("the number of physical names");
  for (std::int64_t k = 0; k < n; ++k) {
    const int dim = static_cast<int>(c.Int("a physical dimension"));
    const int tag = static_cast<int>(c.Int("a physical tag"));
    r->names[{dim, tag}] = c.Next("a physical name").text;
  }
  c.Expect("$EndPhysicalNames");
}

void ReadEntities(Cursor& c, GmshReading* r) {
  r->have_entities = true;
  std::int64_t counts[4];
  for (auto& n : counts) n = c.Count("an entity count");
  for (int dim = 0; dim < 4; ++dim) {
    for (std::int64_t k = 0; k < counts[dim]; ++k) {
      const int tag = static_cast<int>(c.Int("an entity tag"));
      // Points have X Y Z; curves, surfaces, volumes a bounding box (6 numbers).
      for (int i = 0; i < (dim == 0 ? 3 : 6); ++i) c.Real("a coordinate");
      const std::int64_t np = c.Count("the number of physical tags");
      auto& tags = r->physical[{dim, tag}];
      for (std::int64_t i = 0; i < np; ++i) tags.push_back(static_cast<int>(c.Int("a tag")));
      if (dim > 0) {
        const std::int64_t nb = c.Count("the number of bounding entities");
        for (std::int64_t i = 0; i < nb; ++i) c.Int("a bounding entity tag");
      }
    }
  }
  c.Expect("$EndEntities");
}

// One block of $Nodes: its tags, then their coordinates (and parametric ones, skipped).
void ReadNodeBlock(Cursor& c, std::int64_t total, GmshReading* r) {
  GmshMesh& mesh = r->mesh;
  const int dim = static_cast<int>(c.Int("an entity dimension"));
  c.Int("an entity tag");
  const std::int64_t parametric = c.Int("the parametric flag");
  const std::int64_t n = c.Count("the number of nodes in the block");
  const std::size_t first = mesh.node_tags.size();
  for (std::int64_t k = 0; k < n; ++k) {
    const std::int64_t tag = c.Int("a node tag");
    if (r->node_index.count(tag)) c.Fail("node tag " + std::to_string(tag) + " appears twice");
    if (static_cast<std::int64_t>(mesh.node_tags.size()) >= total) {
      c.Fail("more nodes than the $Nodes header's " + std::to_string(total));
    }
    r->node_index[tag] = static_cast<int>(mesh.node_tags.size());
    mesh.node_tags.push_back(tag);
  }
  for (std::int64_t k = 0; k < n; ++k) {
    const Eigen::Index row = static_cast<Eigen::Index>(first + k);
    for (int i = 0; i < 3; ++i) mesh.coordinates(row, i) = c.Real("a node coordinate");
    if (parametric != 0) {
      for (int i = 0; i < dim; ++i) c.Real("a parametric coordinate");
    }
  }
}

void ReadNodes(Cursor& c, std::size_t text_size, GmshReading* r) {
  r->have_nodes = true;
  const std::int64_t blocks = c.Count("the number of node blocks");
  const std::int64_t total = c.Count("the number of nodes");
  c.Int("the minimum node tag");
  c.Int("the maximum node tag");
  // The header's count is trusted only as far as the file could hold that many nodes (a
  // tag and three coordinates take at least 8 bytes): it sizes the coordinate matrix
  // before a single node is read (found by fuzz/gmsh_fuzzer: 1e8 nodes, 2.4 GB).
  if (total > static_cast<std::int64_t>(text_size / 8)) {
    c.Fail("the $Nodes header announces " + std::to_string(total) +
           " nodes, more than the file can hold");
  }
  r->mesh.coordinates.resize(total, 3);
  for (std::int64_t b = 0; b < blocks; ++b) ReadNodeBlock(c, total, r);
  if (static_cast<std::int64_t>(r->mesh.node_tags.size()) != total) {
    c.Fail("the $Nodes header announces " + std::to_string(total) + " nodes, the blocks hold " +
           std::to_string(r->mesh.node_tags.size()));
  }
  c.Expect("$EndNodes");
}

// The nodes per element of a block's type; a type we do not read is refused with what to use.
int SupportedNodesOf(Cursor& c, std::int64_t type, int dim) {
  const int per = NodesOf(type);
  if (per == 0 && dim == 3) {
    c.Fail("element type " + std::to_string(type) + " (" + ElementName(type) +
           ") is not supported: a 3-D body must be 8-node hexahedra (type 5); get them "
           "with transfinite volumes (Transfinite Volume{..}; Recombine Surface{..}; "
           "Recombine Volume{..}) and write with gmsh -3 -format msh41");
  }
  if (per == 0) {
    c.Fail("element type " + std::to_string(type) + " (" + ElementName(type) +
           ") is not supported: only 4-node quadrangles (type 3) make the body, with "
           "2-node lines (type 1) and points (type 15) for physical groups");
  }
  return per;
}

// Hexahedra and quadrangles go to the mesh (quadrangles also by entity, as faces of a 3-D
// mesh); lines and points by entity, for the groups.
void KeepElement(std::int64_t tag, std::int64_t type, std::pair<int, int> entity,
                 const std::array<std::int64_t, 8>& nodes, GmshReading* r) {
  GmshMesh& mesh = r->mesh;
  if (type == 5) {
    mesh.hex_tags.push_back(tag);
    mesh.hexes.push_back(nodes);
  } else if (type == 3) {
    mesh.quad_tags.push_back(tag);
    mesh.quads.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
    r->entity_faces[entity].push_back(mesh.quads.back());
  } else if (type == 1) {
    r->entity_edges[entity].push_back({nodes[0], nodes[1]});
    r->entity_nodes[entity].push_back(nodes[0]);
    r->entity_nodes[entity].push_back(nodes[1]);
  } else {
    r->entity_nodes[entity].push_back(nodes[0]);
  }
}

void ReadElementBlock(Cursor& c, GmshReading* r) {
  const int dim = static_cast<int>(c.Int("an entity dimension"));
  const int entity = static_cast<int>(c.Int("an entity tag"));
  const std::int64_t type = c.Int("an element type");
  const int per = SupportedNodesOf(c, type, dim);
  const std::int64_t n = c.Count("the number of elements in the block");
  for (std::int64_t k = 0; k < n; ++k) {
    const std::int64_t tag = c.Int("an element tag");
    std::array<std::int64_t, 8> nodes{};
    for (int i = 0; i < per; ++i) {
      nodes[i] = c.Int("a node tag");
      if (!r->node_index.count(nodes[i])) {
        c.Fail("element " + std::to_string(tag) + " names node " + std::to_string(nodes[i]) +
               ", which is not in $Nodes");
      }
    }
    KeepElement(tag, type, {dim, entity}, nodes, r);
  }
}

void ReadElements(Cursor& c, GmshReading* r) {
  r->have_elements = true;
  if (!r->have_nodes) c.Fail("$Elements before $Nodes");
  const std::int64_t blocks = c.Count("the number of element blocks");
  c.Count("the number of elements");
  c.Int("the minimum element tag");
  c.Int("the maximum element tag");
  for (std::int64_t b = 0; b < blocks; ++b) ReadElementBlock(c, r);
  c.Expect("$EndElements");
}

// One section, by its opening word.
void ReadSection(Cursor& c, std::size_t text_size, GmshReading* r) {
  const Token section = c.Next("a section");
  if (section.text == "$MeshFormat") {
    c.Next("version");
    c.Next("file type");
    c.Next("data size");
    c.Expect("$EndMeshFormat");
  } else if (section.text == "$PhysicalNames") {
    ReadPhysicalNames(c, r);
  } else if (section.text == "$Entities") {
    ReadEntities(c, r);
  } else if (section.text == "$Nodes") {
    ReadNodes(c, text_size, r);
  } else if (section.text == "$Elements") {
    ReadElements(c, r);
  } else if (section.text.size() > 1 && section.text[0] == '$') {
    // Sections we do not use ($Comments, $Periodic, $NodeData, ...): skip to their end.
    const std::string end = "$End" + section.text.substr(1);
    while (!c.done() && c.Peek() != end) c.Next(end.c_str());
    c.Expect(end);
  } else {
    c.Fail("expected a section ($Name), got '" + section.text + "'");
  }
}

// A physical group: the elements of every entity of its dimension that carries its tag.
GmshMesh::Group ResolveGroup(const std::pair<int, int>& key, const std::string& name,
                             const GmshReading& r) {
  GmshMesh::Group g;
  g.dim = key.first;
  g.tag = key.second;
  g.name = name;
  for (const auto& [entity, tags] : r.physical) {
    if (entity.first != g.dim || std::find(tags.begin(), tags.end(), g.tag) == tags.end()) {
      continue;
    }
    auto e = r.entity_edges.find(entity);
    if (e != r.entity_edges.end())
      g.edges.insert(g.edges.end(), e->second.begin(), e->second.end());
    auto n = r.entity_nodes.find(entity);
    if (n != r.entity_nodes.end())
      g.nodes.insert(g.nodes.end(), n->second.begin(), n->second.end());
    // In a 3-D mesh the quadrangles are boundary faces; in a plane mesh they are the body.
    auto f = r.entity_faces.find(entity);
    if (!r.mesh.hexes.empty() && f != r.entity_faces.end()) {
      g.faces.insert(g.faces.end(), f->second.begin(), f->second.end());
      for (const auto& face : f->second) g.nodes.insert(g.nodes.end(), face.begin(), face.end());
    }
  }
  std::sort(g.nodes.begin(), g.nodes.end());
  g.nodes.erase(std::unique(g.nodes.begin(), g.nodes.end()), g.nodes.end());
  return g;
}

}  // namespace

GmshMesh ParseGmsh(const std::string& text, const std::string& file) {
  CheckHeader(text, file);
  Cursor c(Tokenize(text, file), file);
  GmshReading r;
  while (!c.done()) ReadSection(c, text.size(), &r);
  if (!r.have_nodes || !r.have_elements) {
    c.Fail("the file has no $Nodes or no $Elements section");
  }
  if (!r.names.empty() && !r.have_entities) {
    c.Fail("physical names without an $Entities section: cannot tell which entities they name");
  }
  for (const auto& [key, name] : r.names) r.mesh.groups.push_back(ResolveGroup(key, name, r));
  return std::move(r.mesh);
}

}  // namespace cb::io
