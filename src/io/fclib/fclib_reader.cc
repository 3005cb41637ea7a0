// Reads FCLIB files with HDF5's C API rather than libfclib's reader: that reader exits the
// process on any HDF5 failure and reads each dataset into a buffer sized from the file's own
// m, n and nz without checking the dataset's extent, so a damaged file would end or corrupt the
// run instead of being refused with a message (docs/problem-files.md).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "io/fclib/fclib_matrix.h"
#include "io/fclib/hdf5_file.h"
#include "io/fclib_file.h"
#include "io/input_error.h"
#include "io/problem_name.h"
#include "model/complementarity_model.h"
#include "model/linear_contact_model.h"

namespace cb::io {

namespace {

// M in the finite-element files is symmetric only to ~4e-7 relative (rounding in the writer's
// assembly); above this it is not a rounding difference and the file is refused.
constexpr double kSymmetryTolerance = 1e-6;

struct Layout {
  std::string root;  // "/fclib_local" or "/fclib_global"
  bool global = false;
  int spacedim = 0;
};

Layout ReadLayout(const Hdf5File& file) {
  Layout layout;
  if (file.Has("/fclib_global")) {
    layout = {"/fclib_global", true, 0};
  } else if (file.Has("/fclib_local")) {
    layout = {"/fclib_local", false, 0};
  } else if (file.Has("/fclib_global_rolling")) {
    throw InputError(file.name(), "/fclib_global_rolling",
                     "rolling-friction problems are not read (only /fclib_local and "
                     "/fclib_global)");
  } else {
    throw InputError(file.name(), "", "no /fclib_local or /fclib_global group: not an FCLIB file");
  }
  const std::string path = layout.root + "/spacedim";
  const long long d = file.Integer(path);
  if (d != 2 && d != 3) {
    throw InputError(file.name(), path, "must be 2 or 3, got " + std::to_string(d));
  }
  layout.spacedim = static_cast<int>(d);
  return layout;
}

Vec ReadVector(const Hdf5File& file, const std::string& path, Eigen::Index size) {
  const std::vector<double> v = file.Reals(path, static_cast<std::size_t>(size));
  if (static_cast<Eigen::Index>(v.size()) != size) {
    throw InputError(
        file.name(), path,
        "has " + std::to_string(v.size()) + " entries, expected " + std::to_string(size));
  }
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!std::isfinite(v[k])) {
      throw InputError(file.name(), path + "[" + std::to_string(k) + "]", "not finite");
    }
  }
  return Eigen::Map<const Vec>(v.data(), size);
}

// The number of contacts from a dimension that holds spacedim entries per contact.
int Contacts(const Hdf5File& file, const std::string& path, Eigen::Index size, int spacedim) {
  if (size % spacedim != 0) {
    throw InputError(
        file.name(), path,
        std::to_string(size) + " is not a multiple of spacedim = " + std::to_string(spacedim));
  }
  return static_cast<int>(size / spacedim);
}

// The selection of the normal components: column p is e_{spacedim p}.
SpMat NormalSelection(int contacts, int spacedim) {
  std::vector<Triplet> t;
  t.reserve(contacts);
  for (int p = 0; p < contacts; ++p) t.emplace_back(p * spacedim, p, 1.0);
  SpMat s(static_cast<Eigen::Index>(contacts) * spacedim, contacts);
  s.setFromTriplets(t.begin(), t.end());
  return s;
}

Vec NormalEntries(const Vec& v, int spacedim) {
  Vec n(v.size() / spacedim);
  for (Eigen::Index p = 0; p < n.size(); ++p) n(p) = v(p * spacedim);
  return n;
}

// Friction: zero reads silently; nonzero is refused unless friction=ignore, and then noted.
void DropFriction(const Hdf5File& file, const std::string& path, const Vec& mu, const Parameters& p,
                  std::vector<std::string>* notes) {
  for (Eigen::Index k = 0; k < mu.size(); ++k) {
    if (mu(k) < 0.0) {
      throw InputError(file.name(), path + "[" + std::to_string(k) + "]", "must be >= 0");
    }
  }
  const Eigen::Index rough = (mu.array() > 0.0).count();
  if (rough == 0) return;
  std::ostringstream what;
  what << rough << " of " << mu.size() << " contacts have friction (mu up to " << mu.maxCoeff()
       << ")";
  if (p.Choice("friction") != "ignore") {
    throw InputError(file.name(), path,
                     what.str() +
                         ": this suite solves frictionless problems; --set "
                         "friction=ignore drops friction (mu = 0), which changes the "
                         "problem");
  }
  notes->push_back("friction dropped: " + what.str() + " set to mu = 0");
}

Parameters FclibParameters(double length, double force) {
  Parameters p;
  DeclareScaleParameters(length, force, &p);
  p.DeclareChoice("friction", "refuse",
                  "a file with mu > 0: refuse it, or ignore friction (solve with mu = 0)",
                  {"refuse", "ignore"});
  return p;
}

Parameters ApplyFclibSettings(const std::string& file, double length, double force,
                              const std::map<std::string, std::string>& settings) {
  Parameters p = FclibParameters(length, force);
  try {
    p.Apply(settings);
  } catch (const std::invalid_argument& e) {
    throw InputError(file, "", std::string("--set: ") + e.what());
  }
  return p;
}

double MaxAbs(const SpMat& m) {
  double largest = 0.0;
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k) {
    largest = std::max(largest, std::abs(m.valuePtr()[k]));
  }
  return largest;
}

// (M + M^T) / 2 when M is symmetric to kSymmetryTolerance, with a note of how far it was.
SpMat SymmetricStiffness(const Hdf5File& file, const std::string& path, const SpMat& m,
                         std::vector<std::string>* notes) {
  if (m.rows() != m.cols()) {
    throw InputError(
        file.name(), path,
        "must be square, is " + std::to_string(m.rows()) + " x " + std::to_string(m.cols()));
  }
  const SpMat transpose = m.transpose();
  const double asymmetry = MaxAbs(SpMat(transpose - m)) / std::max(MaxAbs(m), 1e-300);
  if (asymmetry > kSymmetryTolerance) {
    std::ostringstream s;
    s << "not symmetric: max |M - M^T| / max |M| = " << asymmetry << " > " << kSymmetryTolerance;
    throw InputError(file.name(), path, s.str());
  }
  if (asymmetry == 0.0) return m;
  std::ostringstream s;
  s << "M symmetrised: (M + M^T) / 2, max |M - M^T| / max |M| was " << asymmetry;
  notes->push_back(s.str());
  return SpMat(0.5 * (m + transpose));
}

Problem ReadLocal(const Hdf5File& file, const Layout& layout,
                  const std::map<std::string, std::string>& settings) {
  const std::string& root = layout.root;
  for (const char* mixed : {"/V", "/R"}) {
    if (file.Has(root + mixed)) {
      throw InputError(file.name(), root + mixed,
                       "mixed local problems (V, R, s: equality constraints) are not read");
    }
  }
  const SpMat w = ReadFclibMatrix(file, root + "/W");
  if (w.rows() != w.cols()) {
    throw InputError(file.name(), root + "/W", "must be square");
  }
  const int contacts = Contacts(file, root + "/W/m", w.rows(), layout.spacedim);
  const Vec q = ReadVector(file, root + "/vectors/q", w.rows());
  const Vec mu = ReadVector(file, root + "/vectors/mu", contacts);
  const SpMat select = NormalSelection(contacts, layout.spacedim);
  const SpMat w_nn = SpMat(select.transpose()) * w * select;
  auto model = std::make_shared<ComplementarityModel>(
      ComplementarityModel::Lcp(w_nn, NormalEntries(q, layout.spacedim)));
  double length = 1.0, force = 1.0;
  model->DataScales(&length, &force);
  Problem problem;
  problem.parameters = ApplyFclibSettings(file.name(), length, force, settings);
  DropFriction(file, root + "/vectors/mu", mu, problem.parameters, &problem.notes);
  problem.model = std::move(model);
  problem.from_fclib = true;
  problem.load = 0.0;  // an LCP: (29) at lambda = 0 is w = W_NN z + q_N = -r
  problem.units = "none";
  problem.description =
      "FCLIB local problem: LCP on the normal components, nc = " + std::to_string(contacts) +
      ", spacedim " + std::to_string(layout.spacedim);
  return problem;
}

Problem ReadGlobal(const Hdf5File& file, const Layout& layout,
                   const std::map<std::string, std::string>& settings) {
  const std::string& root = layout.root;
  if (file.Has(root + "/G")) {
    throw InputError(file.name(), root + "/G",
                     "equality constraints (G, b) are not read: the suite's models have no "
                     "multipliers besides the contact reactions");
  }
  std::vector<std::string> notes;
  const SpMat m = SymmetricStiffness(file, root + "/M", ReadFclibMatrix(file, root + "/M"), &notes);
  const SpMat h = ReadFclibMatrix(file, root + "/H");
  if (h.rows() != m.rows()) {
    throw InputError(file.name(), root + "/H/m",
                     std::to_string(h.rows()) + " rows, M has " + std::to_string(m.rows()));
  }
  const int contacts = Contacts(file, root + "/H/n", h.cols(), layout.spacedim);
  const Vec f = ReadVector(file, root + "/vectors/f", m.rows());
  const Vec w = ReadVector(file, root + "/vectors/w", h.cols());
  const Vec mu = ReadVector(file, root + "/vectors/mu", contacts);
  const SpMat normals = h * NormalSelection(contacts, layout.spacedim);
  auto model =
      std::make_shared<LinearContactModel>(m, normals, NormalEntries(w, layout.spacedim), f);
  // The data's own sizes (as ComplementarityModel::DataScales): R = ||f||_inf, a typical
  // force, and L = R / ||M||_inf, the displacement M maps onto it; 1 where the data give none.
  const double row_sum = (m.cwiseAbs() * Vec::Ones(m.cols())).maxCoeff();
  const double force = f.lpNorm<Eigen::Infinity>() > 0.0 ? f.lpNorm<Eigen::Infinity>() : 1.0;
  const double length = row_sum > 0.0 ? force / row_sum : 1.0;
  Problem problem;
  problem.parameters = ApplyFclibSettings(file.name(), length, force, settings);
  problem.notes = std::move(notes);
  DropFriction(file, root + "/vectors/mu", mu, problem.parameters, &problem.notes);
  problem.model = std::move(model);
  problem.from_fclib = true;
  problem.load = 1.0;  // M v = H r + f: the load f once
  problem.units = "the file's units";
  problem.description = "FCLIB global problem: linear body, n = " + std::to_string(m.rows()) +
                        ", nc = " + std::to_string(contacts) + ", spacedim " +
                        std::to_string(layout.spacedim);
  return problem;
}

}  // namespace

bool FclibAvailable() { return true; }

Problem LoadFclibFile(const std::string& path, const std::map<std::string, std::string>& settings) {
  const Hdf5File file = Hdf5File::OpenForReading(path);
  const Layout layout = ReadLayout(file);
  Problem problem =
      layout.global ? ReadGlobal(file, layout, settings) : ReadLocal(file, layout, settings);
  try {
    problem.scales = ScalesFrom(problem.parameters);
  } catch (const std::invalid_argument& e) {
    throw InputError(path, "", e.what());  // a scale the data imply: none usable
  }
  problem.loading = LoadingKind::kFixedLoad;
  problem.steps = 1;
  const std::string title = file.OptionalString(layout.root + "/info/title");
  if (!title.empty()) problem.description += " (" + title + ")";
  for (const std::string& note : problem.notes) problem.description += "; " + note;
  problem.name = std::filesystem::path(path).stem().string();
  if (!IsFileSafeName(problem.name)) {
    throw InputError(path, "",
                     "'" + problem.name +
                         "' cannot name the output files (vtk/NAME.pvd): rename the file with "
                         "letters, digits and ._+- only, not first '.' or '-'");
  }
  return problem;
}

namespace {

FclibState ReadState(const Hdf5File& file, const std::string& group, const Layout& layout,
                     Eigen::Index dofs, Eigen::Index local) {
  FclibState state;
  const Vec r = ReadVector(file, group + "/r", local);
  if (layout.global) {
    state.u = ReadVector(file, group + "/v", dofs);
    state.r = -NormalEntries(r, layout.spacedim);
  } else {
    state.u = NormalEntries(r, layout.spacedim);
    state.r = -NormalEntries(ReadVector(file, group + "/u", local), layout.spacedim);
  }
  return state;
}

}  // namespace

FclibAnswers LoadFclibAnswers(const std::string& path) {
  const Hdf5File file = Hdf5File::OpenForReading(path);
  const Layout layout = ReadLayout(file);
  const std::string local_size = layout.root + (layout.global ? "/H/n" : "/W/n");
  const Eigen::Index local = file.Integer(local_size);
  const Eigen::Index dofs = layout.global ? file.Integer(layout.root + "/M/n") : 0;
  FclibAnswers answers;
  if (file.Has("/solution")) {
    answers.has_solution = true;
    answers.solution = ReadState(file, "/solution", layout, dofs, local);
  }
  if (file.Has("/guesses")) {
    const long long count = file.Integer("/guesses/number_of_guesses");
    if (count < 0 || count > 100000) {
      throw InputError(path, "/guesses/number_of_guesses", "must be in 0..100000");
    }
    for (long long k = 1; k <= count; ++k) {
      answers.guesses.push_back(
          ReadState(file, "/guesses/" + std::to_string(k), layout, dofs, local));
    }
  }
  return answers;
}

}  // namespace cb::io
