// What a body problem file (truss, plane-stress Q4, hexahedral solid) reads besides its body,
// and the fields every body problem shares once the body is built. Internal to the
// problem-file reader.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/gmsh.h"
#include "io/json_node.h"
#include "io/problem_file_nodes.h"
#include "io/problem_file_obstacles.h"
#include "model/body_contact_model.h"
#include "model/elastic_body.h"
#include "problems/problem.h"

namespace cb::io::reading {

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
  // The end of a default description: " (F)", F the mesh file's name, for elements read from a
  // Gmsh mesh; "" for inline elements.
  std::string MeshNote() const;

  // The physical group of the mesh a "group" names, of lower dimension than the body.
  const GmshMesh::Group& Group(const JsonNode& ref) const;

  // The nodes an entry names by "node": id or "group": name (exactly one of them).
  std::vector<int> SelectNodes(const JsonNode& entry) const;

  // "supports": which degrees of freedom (node * dim + direction) are fixed.
  std::vector<bool> ReadSupports() const;

  // Nodal forces (one row per node); a force on a supported direction would be lost: refused.
  void AddLoads(const DofMap& dofs, Vec* load) const;

  std::vector<ContactPair> ReadPairs(const Obstacles& obstacles);
  const std::string& PairWhere(int p) const { return pair_where_[p]; }

 private:
  JsonNode root_;
  int dim_;
  std::vector<std::string> pair_where_;
};

// The fields every body problem shares, after the body is built.
Problem FinishBody(BodyInput& in, const std::shared_ptr<const ElasticBody>& body,
                   const Vec& nodal_load, const std::string& file,
                   const std::map<std::string, std::string>& settings);

// The isotropic "material": {"E": > 0, "nu": in (-1, 0.5)} of the continuum bodies.
void ReadIsotropic(const JsonNode& root, double* youngs_modulus, double* poisson_ratio);

// "mesh": {"file": F}, instead of inline "nodes" and "elements": F read relative to the
// problem file's directory.
void OpenMesh(const JsonNode& root, const std::string& directory, BodyInput* in);

}  // namespace cb::io::reading
