#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "problems/builders.h"
#include "problems/problem.h"

namespace cb {

void DeclareScaleParameters(double length, double force, Parameters* parameters) {
  parameters->DeclareReal("length_scale", length,
                          "L of psi(g/L, -r/R, rho): a typical gap, in the problem's length unit",
                          0.0, 1e30, true);
  parameters->DeclareReal(
      "force_scale", force,
      "R of psi(g/L, -r/R, rho): a typical reaction, in the problem's force unit", 0.0, 1e30, true);
}

ContactScales ScalesFrom(const Parameters& parameters) {
  const ContactScales scales{parameters.Real("length_scale"), parameters.Real("force_scale")};
  // A declared value is in (0, 1e30]; the default an LCP's data imply (ComplementarityModel::
  // DataScales: max |q| over the largest row sum of |M|) can over- or underflow, which the step
  // would refuse later as an internal error (issue 30: exit 3).
  for (const auto& [name, value] : {std::pair<const char*, double>{"length_scale", scales.length},
                                    {"force_scale", scales.force}}) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw std::invalid_argument(
          std::string(name) + " is " + std::to_string(value) +
          ", not a positive finite number: the problem's data imply no usable scale (their "
          "largest and smallest entries differ by more than doubles hold); give " +
          name + " in the file or with --set " + name + "=VALUE");
    }
  }
  return scales;
}

Problem MakeBodyProblem(std::shared_ptr<const ElasticBody> body,
                        std::vector<std::shared_ptr<const Obstacle>> obstacles,
                        std::vector<ContactPair> pairs, Vec load, const Parameters& parameters) {
  Problem problem;
  auto model = std::make_shared<BodyContactModel>(std::move(body), std::move(obstacles),
                                                  std::move(pairs), std::move(load));
  problem.model = model;
  problem.body = model;
  problem.scales = ScalesFrom(parameters);
  problem.parameters = parameters;
  return problem;
}

void TraceByArcLength(const Parameters& parameters, int control_dof, std::string control_label,
                      Problem* problem) {
  problem->loading = LoadingKind::kArcLength;
  problem->arc_length = parameters.Real("arc_length");
  problem->steps = parameters.Integer("steps");
  problem->control_dof = control_dof;
  problem->control_label = std::move(control_label);
}

namespace {

template <Parameters (*Defaults)(), Problem (*Build)(const Parameters&)>
ProblemInfo Entry(const std::string& name, const std::string& description) {
  ProblemInfo info;
  info.name = name;
  info.description = description;
  info.defaults = Defaults;
  info.factory = [](const std::map<std::string, std::string>& settings) {
    Parameters p = Defaults();
    p.Apply(settings);
    return Build(p);
  };
  return info;
}

}  // namespace

const std::vector<ProblemInfo>& ProblemRegistry() {
  static const std::vector<ProblemInfo> registry = {
      Entry<BlockDefaults, BuildBlock>(
          "block", "P1: plane-stress Q4 block pressed into a wall and a floor, fixed load"),
      Entry<ArchFlatDefaults, BuildArch>(
          "arch-flat", "P2: two-layer arch truss between two flat obstacles, arc length"),
      Entry<ArchCurvedDefaults, BuildArch>(
          "arch-curved", "P3: two-layer arch truss, flat and cylindrical obstacles, arc length"),
      Entry<HertzDefaults, BuildHertz>(
          "hertz-3d", "3-D: hexahedral block pressed onto a rigid sphere (Hertz), fixed load"),
      Entry<PlateDefaults, BuildPlate>(
          "plate-3d", "3-D: neo-Hookean plate pressed onto a rigid cylinder, arc length"),
      Entry<BarWallDefaults, BuildBarWall>(
          "bar-wall", "verification: a bar pushed against a wall (closed form)"),
      Entry<TwoBarDefaults, BuildTwoBar>(
          "two-bar", "verification: von Mises two-bar truss snap-through (closed form)"),
      Entry<TwoBarObstacleDefaults, BuildTwoBar>(
          "two-bar-obstacle",
          "verification: two-bar truss snapping onto a floor under its apex (closed form)"),
  };
  return registry;
}

std::vector<std::string> ProblemNames() {
  std::vector<std::string> names;
  for (const auto& info : ProblemRegistry()) names.push_back(info.name);
  return names;
}

Problem MakeProblem(const std::string& name, const std::map<std::string, std::string>& settings) {
  for (const auto& info : ProblemRegistry()) {
    if (info.name == name) {
      try {
        Problem problem = info.factory(settings);
        problem.name = info.name;  // builders shared by several entries name the entry here
        return problem;
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("problem '" + name + "': " + e.what());
      }
    }
  }
  std::string valid;
  for (const auto& n : ProblemNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown problem '" + name + "' (valid: " + valid + ")");
}

}  // namespace cb
