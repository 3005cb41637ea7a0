#include "formulations/registry.h"

#include <stdexcept>
#include <utility>

#include "core/library_versions.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "formulations/ipopt/ipopt.h"
#include "formulations/nlopt/nlopt.h"
#include "formulations/nonsmooth/nonsmooth.h"
#include "formulations/petsc/petsc.h"
#include "formulations/petsc_dist/petsc_dist.h"
#include "formulations/siconos/siconos.h"
#include "parallel/processes.h"

namespace cb {

namespace {

// The registry itself: the built-in formulations, then those registered at run time.
std::vector<FormulationInfo>& MutableRegistry() {
  // One line per formulation: name, description, whether its backend was built, factory, and
  // for the PETSc ones whether it is distributed and that it takes `petsc_options`.
  static std::vector<FormulationInfo> registry = {
      {"implicit-fb",
       "implicit smoothed Fischer-Burmeister equations (29)-(33), rho an unknown; eta cases 1-4",
       true, MakeImplicitFb},
      {"nonsmooth-fb", "(29), (30), (33) with the plain FB function, semismooth Newton", true,
       MakeNonsmoothFb},
      {"active-set", "(29), (30), (33) with min(g, -r): primal-dual active set", true,
       MakeActiveSet},
      {"ipopt-energy", "fixed-load energy minimisation s.t. phi(u) <= 0, Ipopt", IpoptAvailable(),
       MakeIpoptEnergy},
      {"ipopt-mpcc", "the step as an MPCC NLP (Scholtes relaxation or penalty), Ipopt",
       IpoptAvailable(), MakeIpoptMpcc},
      {"nlopt-merit", "1/2 ||F||^2 of the implicit smoothed-FB system, NLopt LD_LBFGS",
       NloptAvailable(), MakeNloptMerit},
      {"nlopt-energy", "fixed-load energy NLP, NLopt LD_MMA / LD_CCSAQ / LD_SLSQP",
       NloptAvailable(), MakeNloptEnergy},
      {"nlopt-mpcc", "the step NLP in penalty form, NLopt LD_SLSQP", NloptAvailable(),
       MakeNloptMpcc},
      {"siconos-lemke", "fixed-load step as a dense LCP (displacements eliminated), Siconos Lemke",
       SiconosAvailable(), MakeSiconosLemke},
      {"siconos-newton-fb", "the same LCP, Siconos semismooth Newton on FB with line search",
       SiconosAvailable(), MakeSiconosNewtonFb},
      {"siconos-newton-min", "the same LCP, Siconos Newton on min(z, w) with FB line search",
       SiconosAvailable(), MakeSiconosNewtonMin},
      {"petsc-rsls", "the step as an MCP, PETSc SNESVINEWTONRSLS (reduced-space active set)",
       PetscAvailable(), MakePetscRsls, false, true},
      {"petsc-ssls", "the step as an MCP, PETSc SNESVINEWTONSSLS (semismooth FB)", PetscAvailable(),
       MakePetscSsls, false, true},
      {"dist-implicit-fb", "implicit-fb's equations distributed over MPI, PETSc SNES newtonls",
       DistAvailable(), MakeDistImplicitFb, true, true},
      {"dist-nonsmooth-fb", "nonsmooth-fb's equations distributed over MPI, PETSc SNES newtonls",
       DistAvailable(), MakeDistNonsmoothFb, true, true},
      {"dist-active-set", "active-set's equations distributed over MPI, PETSc SNES newtonls",
       DistAvailable(), MakeDistActiveSet, true, true},
      {"dist-petsc-rsls", "petsc-rsls's MCP distributed over MPI, SNESVINEWTONRSLS",
       DistAvailable(), MakeDistPetscRsls, true, true},
      {"dist-petsc-ssls", "petsc-ssls's MCP distributed over MPI, SNESVINEWTONSSLS",
       DistAvailable(), MakeDistPetscSsls, true, true},
  };
  return registry;
}

bool IsFormulationName(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!letter && c != '-' && c != '_' && c != '.') return false;
  }
  return true;
}

}  // namespace

const std::vector<FormulationInfo>& FormulationRegistry() { return MutableRegistry(); }

void RegisterFormulation(FormulationInfo info) {
  if (!IsFormulationName(info.name)) {
    throw std::invalid_argument("formulation name '" + info.name +
                                "': letters, digits, '-', '_' and '.' only, not empty");
  }
  for (const auto& known : FormulationRegistry()) {
    if (known.name == info.name) {
      throw std::invalid_argument("formulation '" + info.name + "' is already registered");
    }
  }
  if (!info.make) throw std::invalid_argument("formulation '" + info.name + "': no factory");
  MutableRegistry().push_back(std::move(info));
}

std::vector<LinkedLibrary> LinkedLibraries() {
  // One line per library.
  return {
      {"eigen", EigenVersion()}, {"suitesparse", SuiteSparseVersion()},  {"ipopt", IpoptVersion()},
      {"nlopt", NloptVersion()}, {"siconos-numerics", SiconosVersion()}, {"petsc", PetscVersion()},
      {"mpi", MpiVersion()},
  };
}

std::vector<std::string> FormulationNames() {
  std::vector<std::string> names;
  for (const auto& info : FormulationRegistry()) names.push_back(info.name);
  return names;
}

const FormulationInfo* FindFormulation(const std::string& name) {
  for (const auto& info : FormulationRegistry()) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

bool TakesPetscOptions(const std::string& name) {
  const FormulationInfo* info = FindFormulation(name);
  return info != nullptr && info->takes_petsc_options;
}

std::unique_ptr<Formulation> MakeFormulation(const std::string& name,
                                             const FormulationConfig& config) {
  for (const auto& info : FormulationRegistry()) {
    if (info.name != name) continue;
    if (!info.available) {
      throw std::invalid_argument("formulation '" + name +
                                  "' is not available in this build (its dependency was not "
                                  "found at configure time)");
    }
    return info.make(config);
  }
  std::string valid;
  for (const auto& n : FormulationNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown formulation '" + name + "' (valid: " + valid + ")");
}

}  // namespace cb
