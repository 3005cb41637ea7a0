// A reader of Gmsh's ASCII mesh format version 4.1 (gmsh.info/doc/texinfo/gmsh.html, "MSH file
// format"), for plane Q4 meshes and 3-D hexahedral meshes. Plane: the 4-node quadrangles
// (element type 3) are the body; 2-node lines (type 1) and points (type 15) carry the physical
// groups that name edges and nodes for tractions, supports and contact pairs. 3-D (any 8-node
// hexahedron, type 5, in the file): the hexahedra are the body, and quadrangles, lines and
// points carry the groups (quadrangles: faces for tractions). Other versions (2.2, 4.0), binary
// files, and element types other than these are refused with the reason.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace cb::io {

struct GmshMesh {
  struct Group {
    // 0 (points), 1 (curves), 2 (surfaces), 3 (volumes). Surface groups hold faces and nodes
    // only in a 3-D mesh; volume groups are listed with no nodes.
    int dim = 0;
    int tag = 0;
    std::string name;
    std::vector<std::array<std::int64_t, 2>> edges;  // line elements, node tags
    std::vector<std::array<std::int64_t, 4>> faces;  // 3-D mesh: quadrangles, node tags
    std::vector<std::int64_t> nodes;                 // every node of the group, sorted, unique
  };
  std::vector<std::int64_t> node_tags;  // in file order
  Mat coordinates;                      // one row (x, y, z) per node
  std::vector<std::int64_t> quad_tags;  // element tags of the quadrangles, in file order
  std::vector<std::array<std::int64_t, 4>> quads;
  std::vector<std::int64_t> hex_tags;  // element tags of the hexahedra, in file order
  std::vector<std::array<std::int64_t, 8>> hexes;
  std::vector<Group> groups;  // every named physical group
};

// Reads `path`. Throws InputError "PATH: line N: reason" for an unreadable file, another
// version or the binary variant, an unsupported element type, a node or physical tag that is
// not defined, or a malformed section.
GmshMesh ReadGmsh(const std::string& path);
// The same from the file's contents; `file` names it in messages.
GmshMesh ParseGmsh(const std::string& text, const std::string& file);

}  // namespace cb::io
