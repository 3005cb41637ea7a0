#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/directions.h"
#include "io/problem_file.h"
#include "model/complementarity_model.h"
#include "model/obstacle.h"
#include "model/plane_stress_q4.h"
#include "model/solid_hex8.h"
#include "model/truss.h"

namespace cb::io {

namespace {

using OJson = nlohmann::ordered_json;

OJson ToJson(const Point& p) {
  OJson a = OJson::array();
  for (Eigen::Index i = 0; i < p.size(); ++i) a.push_back(p[i]);
  return a;
}

OJson Directions(const std::vector<int>& components) {
  OJson a = OJson::array();
  for (int c : components) a.push_back(kDirectionNames[c]);
  return a;
}

// Top-level fields one per line, arrays of objects or arrays one item per line: readable and
// diff-friendly, and exact (nlohmann writes the shortest text that reads back to each double).
std::string Layout(const OJson& j) {
  std::string out = "{\n";
  bool first = true;
  for (const auto& [key, value] : j.items()) {
    out += first ? "" : ",\n";
    first = false;
    out += "  " + OJson(key).dump() + ": ";
    if (value.is_array() && !value.empty() && (value[0].is_object() || value[0].is_array())) {
      out += "[\n";
      for (std::size_t i = 0; i < value.size(); ++i) {
        out += "    " + value[i].dump() + (i + 1 < value.size() ? ",\n" : "\n");
      }
      out += "  ]";
    } else {
      out += value.dump();
    }
  }
  return out + "\n}\n";
}

// "kind" and the body's own fields: dimension and members, or material and elements.
void WriteBodyKind(const Problem& problem, OJson* j) {
  const ElasticBody& body = problem.body->body();
  const int dim = body.dim();
  OJson nodes = OJson::array();
  for (int n = 0; n < body.num_nodes(); ++n)
    nodes.push_back({{"id", n}, {"x", ToJson(body.reference(n))}});
  if (const auto* truss = dynamic_cast<const Truss*>(&body)) {
    (*j)["kind"] = "truss";
    (*j)["dimension"] = dim;
    (*j)["nodes"] = nodes;
    OJson members = OJson::array();
    for (const auto& m : truss->members()) {
      members.push_back({{"nodes", {m.node_i, m.node_j}}, {"E", m.youngs_modulus}, {"A", m.area}});
    }
    (*j)["members"] = members;
  } else if (const auto* q4 = dynamic_cast<const PlaneStressQ4*>(&body)) {
    (*j)["kind"] = "plane-stress-q4";
    (*j)["deformation"] = "small";
    (*j)["thickness"] = q4->material().thickness;
    (*j)["material"] = {{"E", q4->material().youngs_modulus}, {"nu", q4->material().poisson_ratio}};
    (*j)["nodes"] = nodes;
    OJson elements = OJson::array();
    for (const auto& e : q4->elements()) elements.push_back({{"nodes", {e[0], e[1], e[2], e[3]}}});
    (*j)["elements"] = elements;
  } else if (const auto* hex = dynamic_cast<const SolidHex8*>(&body)) {
    (*j)["kind"] = "solid-hex8";
    (*j)["deformation"] = hex->kinematics() == SolidKinematics::kSmallStrain ? "small" : "large";
    (*j)["material"] = {{"E", hex->material().youngs_modulus},
                        {"nu", hex->material().poisson_ratio}};
    (*j)["nodes"] = nodes;
    OJson elements = OJson::array();
    for (const auto& e : hex->elements()) elements.push_back({{"nodes", e}});
    (*j)["elements"] = elements;
  } else {
    throw std::invalid_argument("problem '" + problem.name +
                                "': its body is not a truss, a plane-stress Q4 mesh or a "
                                "hexahedral solid");
  }
}

// Supported directions and nodal forces (the load pattern), node by node.
void WriteSupportsAndLoads(const BodyContactModel& model, OJson* j) {
  const ElasticBody& body = model.body();
  const int dim = body.dim();
  OJson supports = OJson::array();
  OJson loads = OJson::array();
  const Vec& f = model.load_pattern();
  for (int n = 0; n < body.num_nodes(); ++n) {
    std::vector<int> fixed;
    Point force = Point::Zero(dim);
    bool loaded = false;  // ||force||^2 > 0: some component's square is (a sum of squares is 0
                          // only when each is), tested without Eigen's vectorised sum, which
                          // GCC 12 misreads here as a read past the 3 entries of a Point
    for (int c = 0; c < dim; ++c) {
      const int dof = body.dofs().dof(n, c);
      if (dof < 0) {
        fixed.push_back(c);
      } else {
        force[c] = f[dof];
        loaded = loaded || force[c] * force[c] > 0.0;
      }
    }
    if (!fixed.empty()) supports.push_back({{"node", n}, {"fixed", Directions(fixed)}});
    if (loaded) loads.push_back({{"node", n}, {"force", ToJson(force)}});
  }
  (*j)["supports"] = supports;
  (*j)["loads"] = loads;
}

// The obstacles, with ids obstacle0, obstacle1, ...
void WriteObstacles(const Problem& problem, OJson* j) {
  const BodyContactModel& model = *problem.body;
  OJson obstacles = OJson::array();
  for (std::size_t k = 0; k < model.obstacles().size(); ++k) {
    const Obstacle* o = model.obstacles()[k].get();
    const std::string id = "obstacle" + std::to_string(k);
    if (const auto* h = dynamic_cast<const HalfSpace*>(o)) {
      obstacles.push_back({{"id", id},
                           {"type", "half-space"},
                           {"point", ToJson(h->point())},
                           {"normal", ToJson(h->normal())}});
    } else if (const auto* b = dynamic_cast<const Ball*>(o)) {
      obstacles.push_back({{"id", id},
                           {"type", "ball"},
                           {"centre", ToJson(b->centre())},
                           {"radius", b->radius()},
                           {"side", b->side() == Ball::Side::kSolid ? "solid" : "cavity"}});
    } else if (const auto* c = dynamic_cast<const Cylinder*>(o)) {
      obstacles.push_back({{"id", id},
                           {"type", "cylinder"},
                           {"point", ToJson(c->point())},
                           {"axis", ToJson(c->axis())},
                           {"radius", c->radius()},
                           {"side", c->side() == Ball::Side::kSolid ? "solid" : "cavity"}});
    } else {
      throw std::invalid_argument("problem '" + problem.name + "': obstacle " + std::to_string(k) +
                                  " (" + o->Describe() + ") has no problem-file form");
    }
  }
  (*j)["obstacles"] = obstacles;
}

// The contact pairs, and the control (the node and direction of the recorded displacement).
void WritePairsAndControl(const Problem& problem, OJson* j) {
  const BodyContactModel& model = *problem.body;
  const ElasticBody& body = model.body();
  const int dim = body.dim();
  OJson pairs = OJson::array();
  for (const auto& p : model.pairs()) {
    pairs.push_back({{"node", p.node}, {"obstacle", "obstacle" + std::to_string(p.obstacle)}});
  }
  (*j)["contact_pairs"] = pairs;
  if (problem.control_dof >= 0) {
    for (int n = 0; n < body.num_nodes(); ++n) {
      for (int c = 0; c < dim; ++c) {
        if (body.dofs().dof(n, c) == problem.control_dof) {
          (*j)["control"] = {
              {"node", n}, {"direction", kDirectionNames[c]}, {"label", problem.control_label}};
        }
      }
    }
  }
}

void WriteBody(const Problem& problem, OJson* j) {
  WriteBodyKind(problem, j);
  WriteSupportsAndLoads(*problem.body, j);
  WriteObstacles(problem, j);
  WritePairsAndControl(problem, j);
}

}  // namespace

std::string ProblemToJson(const Problem& problem) {
  if (problem.model == nullptr)
    throw std::invalid_argument("ProblemToJson: the problem has no model");
  OJson j;
  j["kind"] = "";  // first in the file; set below
  j["version"] = 1;
  j["name"] = problem.name;
  j["description"] = problem.description;
  j["units"] = problem.units;
  OJson parameters = OJson::object();
  for (const auto& e : problem.parameters.entries()) parameters[e.name] = e.value;
  j["source"] = {{"problem", problem.name}, {"parameters", parameters}};
  j["length_scale"] = problem.scales.length;
  j["force_scale"] = problem.scales.force;
  if (problem.body != nullptr) {
    if (problem.loading == LoadingKind::kFixedLoad) {
      j["analysis"] = "fixed-load";
      j["load"] = problem.load;
    } else {
      j["analysis"] = "arc-length";
      j["arc_length"] = problem.arc_length;
      j["steps"] = problem.steps;
    }
    WriteBody(problem, &j);
    return Layout(j);
  }
  const auto* lcp = dynamic_cast<const ComplementarityModel*>(problem.model.get());
  if (lcp == nullptr || !lcp->is_linear()) {
    throw std::invalid_argument("problem '" + problem.name +
                                "' has no problem-file form (only bodies and LCPs do)");
  }
  j["kind"] = "lcp";
  j["analysis"] = "fixed-load";
  const int n = lcp->num_dofs();
  const Vec zero = Vec::Zero(n);
  SpMat m;
  lcp->Stiffness(zero, &m);  // M
  Vec q;
  lcp->InternalForce(zero, &q);  // M 0 + q
  OJson entries = OJson::array();
  for (int c = 0; c < m.outerSize(); ++c) {
    for (SpMat::InnerIterator it(m, c); it; ++it) {
      entries.push_back({static_cast<int>(it.row()), c, it.value()});
    }
  }
  j["M"] = {{"rows", n}, {"cols", n}, {"entries", entries}};
  j["q"] = OJson::array();
  for (int i = 0; i < n; ++i) j["q"].push_back(q[i]);
  return Layout(j);
}

}  // namespace cb::io
