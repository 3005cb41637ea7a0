#include "formulations/nlopt/nlopt_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cb {

namespace {

bool Positive(double v) { return v > 0.0 && std::isfinite(v); }
bool NonNegative(double v) { return v >= 0.0 && std::isfinite(v); }

// `ok`, with *why = `reason` when not: the checks below chain these with &&, so the first
// failing one gives the reason.
bool Require(bool ok, const char* reason, std::string* why) {
  if (!ok) *why = reason;
  return ok;
}

// NLopt's stopping tests, which every formulation sets (NloptRun::SetStops).
bool AreValidStops(double ftol_rel, double xtol_rel, int maxeval, std::string* why) {
  return Require(NonNegative(ftol_rel) && NonNegative(xtol_rel),
                 "ftol_rel and xtol_rel must be >= 0", why) &&
         Require(maxeval >= 1, "maxeval must be >= 1", why);
}

// Reads the options of the NLopt formulation `name`: its own keys by `read_own`, then the
// stopping tests every formulation sets (AreValidStops); refuses an unknown key or an invalid
// value naming the formulation.
template <class Options, class ReadOwn>
Options ReadOptions(const char* name, const FormulationConfig& config, ReadOwn read_own) {
  OptionReader reader(name, config.options);
  Options o;
  read_own(&reader, &o);
  o.ftol_rel = reader.GetReal("ftol_rel", o.ftol_rel);
  o.xtol_rel = reader.GetReal("xtol_rel", o.xtol_rel);
  o.maxeval = reader.GetInteger("maxeval", o.maxeval);
  reader.Finish();
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument(std::string(name) + " options: " + why);
  return o;
}

}  // namespace

bool NloptMeritOptions::IsValid(std::string* why) const {
  return Require(algorithm == "lbfgs" || algorithm == "tnewton",
                 "algorithm must be lbfgs or tnewton", why) &&
         IsValidSmoothing(eta, gamma_tol, rho_min, why) &&
         Require(Positive(residual_tol), "residual_tol must be positive", why) &&
         Require(Positive(merit_scale), "merit_scale must be positive", why) &&
         AreValidStops(ftol_rel, xtol_rel, maxeval, why) &&
         Require(memory >= 0, "memory must be >= 0", why);
}

bool NloptEnergyOptions::IsValid(std::string* why) const {
  return Require(algorithm == "mma" || algorithm == "ccsaq" || algorithm == "slsqp",
                 "algorithm must be mma, ccsaq or slsqp", why) &&
         AreValidStops(ftol_rel, xtol_rel, maxeval, why) &&
         Require(NonNegative(constraint_tol), "constraint_tol must be >= 0", why) &&
         Require(NonNegative(active_tol), "active_tol must be >= 0", why) &&
         Require(max_dense_size >= 1, "max_dense_size must be >= 1", why) &&
         Require(Positive(max_gradient_entries), "max_gradient_entries must be positive", why);
}

bool NloptMpccOptions::IsValid(std::string* why) const {
  return Require(Positive(weight), "weight must be positive", why) &&
         Require(Positive(bound_push), "bound_push must be positive", why) &&
         Require(Positive(residual_tol), "residual_tol must be positive", why) &&
         AreValidStops(ftol_rel, xtol_rel, maxeval, why) &&
         Require(max_dense_size >= 1, "max_dense_size must be >= 1", why);
}

NloptMeritOptions ReadNloptMeritOptions(const FormulationConfig& config) {
  return ReadOptions<NloptMeritOptions>(
      "nlopt-merit", config, [&config](OptionReader* reader, NloptMeritOptions* o) {
        o->eta = static_cast<EtaCase>(config.eta);  // checked by IsValid
        o->algorithm = reader->GetChoice("algorithm", o->algorithm, {"lbfgs", "tnewton"});
        o->gamma_tol = reader->GetReal("gamma_tol", o->gamma_tol);
        o->rho_min = reader->GetReal("rho_min", o->rho_min);
        o->residual_tol = reader->GetReal("residual_tol", config.solver_options.residual_tol);
        o->merit_scale = reader->GetReal("merit_scale", o->merit_scale);
        o->memory = reader->GetInteger("memory", o->memory);
      });
}

NloptEnergyOptions ReadNloptEnergyOptions(const FormulationConfig& config) {
  return ReadOptions<NloptEnergyOptions>(
      "nlopt-energy", config, [](OptionReader* reader, NloptEnergyOptions* o) {
        o->algorithm = reader->GetChoice("algorithm", o->algorithm, {"mma", "ccsaq", "slsqp"});
        o->constraint_tol = reader->GetReal("constraint_tol", o->constraint_tol);
        o->active_tol = reader->GetReal("active_tol", o->active_tol);
        o->max_dense_size = reader->GetInteger("max_dense_size", o->max_dense_size);
        o->max_gradient_entries = reader->GetReal("max_gradient_entries", o->max_gradient_entries);
      });
}

NloptMpccOptions ReadNloptMpccOptions(const FormulationConfig& config) {
  return ReadOptions<NloptMpccOptions>(
      "nlopt-mpcc", config, [](OptionReader* reader, NloptMpccOptions* o) {
        o->weight = reader->GetReal("weight", o->weight);
        o->residual_tol = reader->GetReal("residual_tol", o->residual_tol);
        o->bound_push = reader->GetReal("bound_push", o->bound_push);
        o->max_dense_size = reader->GetInteger("max_dense_size", o->max_dense_size);
      });
}

}  // namespace cb
