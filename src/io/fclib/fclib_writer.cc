// A linear problem as an FCLIB global problem with mu = 0 (src/io/fclib_file.h). Written with
// HDF5's C API in the layout of FCLIB's own writer (groups, dataset names, int and double
// types, compressed-column matrices), so FCLIB's reader and Siconos read it.
#include <algorithm>
#include <stdexcept>

#include "io/fclib/fclib_matrix.h"
#include "io/fclib/hdf5_file.h"
#include "io/fclib_file.h"

namespace cb::io {

namespace {

// The global problem's data, from a linear model at the problem's fixed load. grad pi(u) =
// K u + grad pi(0) for a linear model, and (9) reads K u - (lambda f - grad pi(0)) + N r = 0
// with N = -grad phi^T, which is FCLIB's M v = H r + f with v = u, r_N = -r.
struct GlobalData {
  SpMat stiffness;
  SpMat normals;  // n x nc
  Vec force;
  Vec initial_gaps;
};

GlobalData FromModel(const Problem& problem) {
  const ContactModel& model = *problem.model;
  if (!model.is_linear()) {
    throw std::invalid_argument("FCLIB export: '" + problem.name +
                                "' is not small-deformation (FCLIB problems are linear)");
  }
  if (!model.has_energy()) {
    throw std::invalid_argument("FCLIB export: '" + problem.name +
                                "' has no energy (a non-symmetric M; FCLIB's M is symmetric)");
  }
  const Vec zero = Vec::Zero(model.num_dofs());
  GlobalData data;
  model.Stiffness(zero, &data.stiffness);
  Vec internal;
  model.InternalForce(zero, &internal);
  data.force = problem.load * model.load_pattern() - internal;
  SpMat jacobian;
  model.GapJacobian(zero, &jacobian);
  data.normals = -SpMat(jacobian.transpose());
  Vec phi;
  model.Gaps(zero, &phi);
  data.initial_gaps = -phi;
  return data;
}

// spacedim columns per contact: the normal, then zero tangential columns (mu = 0 makes them
// irrelevant; FCLIB has no frictionless form, so this is the smallest it accepts).
SpMat Spread(const SpMat& normals, int spacedim) {
  std::vector<Triplet> t;
  for (int p = 0; p < normals.outerSize(); ++p) {
    for (SpMat::InnerIterator it(normals, p); it; ++it) {
      t.emplace_back(static_cast<int>(it.row()), p * spacedim, it.value());
    }
  }
  SpMat h(normals.rows(), normals.cols() * spacedim);
  h.setFromTriplets(t.begin(), t.end());
  return h;
}

Vec Spread(const Vec& normal_entries, int spacedim) {
  Vec v = Vec::Zero(normal_entries.size() * spacedim);
  for (Eigen::Index p = 0; p < normal_entries.size(); ++p) v(p * spacedim) = normal_entries(p);
  return v;
}

void WriteState(const Hdf5File& file, const std::string& group, const GlobalData& data,
                const FclibState& state, int spacedim) {
  if (state.u.size() != data.stiffness.rows() || state.r.size() != data.normals.cols()) {
    throw std::invalid_argument("FCLIB export: a state of sizes " + std::to_string(state.u.size()) +
                                ", " + std::to_string(state.r.size()) + " for a problem of " +
                                std::to_string(data.stiffness.rows()) + " dofs and " +
                                std::to_string(data.normals.cols()) + " pairs");
  }
  file.MakeGroup(group);
  const Vec gaps = SpMat(data.normals.transpose()) * state.u + data.initial_gaps;
  const Vec u = Spread(gaps, spacedim);
  const Vec r = Spread(Vec(-state.r), spacedim);
  file.WriteReals(group + "/v", state.u.data(), state.u.size());
  file.WriteReals(group + "/u", u.data(), u.size());
  file.WriteReals(group + "/r", r.data(), r.size());
}

}  // namespace

void WriteFclibFile(const Problem& problem, const std::string& path, const FclibState* solution,
                    const FclibState* guess) {
  const GlobalData data = FromModel(problem);
  const int spacedim = problem.body && problem.body->body().dim() == 3 ? 3 : 2;
  const int contacts = static_cast<int>(data.normals.cols());
  Hdf5File file = Hdf5File::Create(path);
  file.MakeGroup("/fclib_global");
  file.WriteIntegers("/fclib_global/spacedim", {spacedim});
  WriteFclibMatrix(file, "/fclib_global/M", data.stiffness);
  WriteFclibMatrix(file, "/fclib_global/H", Spread(data.normals, spacedim));
  file.MakeGroup("/fclib_global/vectors");
  const Vec w = Spread(data.initial_gaps, spacedim);
  const Vec mu = Vec::Zero(contacts);
  file.WriteReals("/fclib_global/vectors/f", data.force.data(), data.force.size());
  file.WriteReals("/fclib_global/vectors/w", w.data(), w.size());
  file.WriteReals("/fclib_global/vectors/mu", mu.data(), mu.size());
  file.MakeGroup("/fclib_global/info");
  file.WriteString("/fclib_global/info/title", problem.name);
  file.WriteString("/fclib_global/info/description",
                   "contactbench: " + problem.description + "; frictionless (mu = 0)");
  file.WriteString("/fclib_global/info/math_info", "M symmetric; mu = 0");
  if (solution) WriteState(file, "/solution", data, *solution, spacedim);
  if (guess) {
    file.MakeGroup("/guesses");
    file.WriteIntegers("/guesses/number_of_guesses", {1});
    WriteState(file, "/guesses/1", data, *guess, spacedim);
  }
  file.Close();
}

}  // namespace cb::io
