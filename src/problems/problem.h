// A named benchmark problem: the contact model built from its parameters, with the loading
// path the report traces on it.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "model/body_contact_model.h"
#include "problems/parameters.h"
#include "step/step_problem.h"

namespace cb {

// How the problem is loaded: one fixed-load solve (P1), or an arc-length path (P2, P3).
enum class LoadingKind { kFixedLoad, kArcLength };

struct Problem {
  std::string name;
  std::string description;
  std::string units;  // how lengths and forces in the records are measured
  std::shared_ptr<const ContactModel> model;
  // The same model seen as a body against obstacles (nodes, pairs), for solution records;
  // null for models that are not mechanical bodies.
  std::shared_ptr<const BodyContactModel> body;
  ContactScales scales;
  LoadingKind loading = LoadingKind::kArcLength;
  double load = 1.0;        // kFixedLoad: the lambda of the single solve
  double arc_length = 0.1;  // kArcLength: theta
  int steps = 100;          // kArcLength: default number of steps
  int control_dof = -1;     // the displacement recorded as control_disp (-1: none)
  std::string control_label;
  Parameters parameters;  // as used to build it
  // What reading the problem changed in it, one sentence each (an FCLIB file's friction
  // dropped, its M symmetrised); run.json records them. Empty for a problem read as written.
  std::vector<std::string> notes;
  // Read from an FCLIB file: each step's record carries the FCLIB error (steps.csv's
  // fclib_error) to set beside published figures. Other problems leave it NaN there, but an
  // LCP's (no factorisation): on a linear body it costs a factorisation of K per step.
  bool from_fclib = false;
  // A problem file's own names, which the records use: each node's id (a Gmsh node's tag) and
  // each obstacle's id, by the model's 0-based index. Empty for a named problem, whose
  // records number nodes and obstacles from 0.
  std::vector<std::int64_t> node_ids;
  std::vector<std::string> obstacle_ids;
};

using ProblemFactory = std::function<Problem(const std::map<std::string, std::string>&)>;

struct ProblemInfo {
  std::string name;
  std::string description;
  ProblemFactory factory;
  std::function<Parameters()> defaults;  // the declared parameters with default values
};

// The registry, in a fixed order: block, arch-flat, arch-curved, the 3-D problems, then
// verification problems.
const std::vector<ProblemInfo>& ProblemRegistry();
std::vector<std::string> ProblemNames();
// Throws std::invalid_argument for an unknown name (listing the valid ones) or a bad setting.
Problem MakeProblem(const std::string& name,
                    const std::map<std::string, std::string>& settings = {});

// The fields every problem of a body against obstacles shares: the model (also as `body`),
// the contact scales read from `parameters`, and the parameters themselves.
Problem MakeBodyProblem(std::shared_ptr<const ElasticBody> body,
                        std::vector<std::shared_ptr<const Obstacle>> obstacles,
                        std::vector<ContactPair> pairs, Vec load, const Parameters& parameters);

// Parameters every problem has: the contact scales of docs/method.md section 2.
void DeclareScaleParameters(double length, double force, Parameters* parameters);
ContactScales ScalesFrom(const Parameters& parameters);

}  // namespace cb
