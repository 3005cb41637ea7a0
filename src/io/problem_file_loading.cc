#include "io/problem_file_loading.h"

namespace cb::io::reading {

Loading ReadLoading(const JsonNode& root) {
  Loading l;
  const JsonNode analysis = root.Field("analysis");
  const std::string kind = analysis.String();
  if (kind == "fixed-load") {
    l.kind = LoadingKind::kFixedLoad;
    if (auto load = root.Optional("load")) l.load = load->Number();
    for (const char* key : {"arc_length", "steps"}) {
      if (root.Has(key)) root.Field(key).Fail("only with \"analysis\": \"arc-length\"");
    }
  } else if (kind == "arc-length") {
    l.kind = LoadingKind::kArcLength;
    l.arc_length = root.Field("arc_length").Positive();
    l.steps = root.Field("steps").PositiveInt();
    if (root.Has("load")) root.Field("load").Fail("only with \"analysis\": \"fixed-load\"");
  } else {
    analysis.Fail("must be \"fixed-load\" or \"arc-length\", got \"" + kind + "\"");
  }
  return l;
}

Parameters RunParameters(double length_scale, double force_scale, const Loading& loading,
                         bool complementarity) {
  Parameters p;
  DeclareScaleParameters(length_scale, force_scale, &p);
  if (complementarity) return p;
  if (loading.kind == LoadingKind::kFixedLoad) {
    p.DeclareReal("load", loading.load, "lambda of the single fixed-load solve", -1e30, 1e30);
  } else {
    p.DeclareReal("arc_length", loading.arc_length, "theta of (33), ||(du, dlambda)||_2", 0.0, 1e30,
                  true);
    p.DeclareInteger("steps", loading.steps, "arc-length steps", 1, 2000000000);
  }
  return p;
}

void ApplySettings(const std::string& file, const std::map<std::string, std::string>& settings,
                   Parameters* p) {
  try {
    p->Apply(settings);
  } catch (const std::invalid_argument& e) {
    throw InputError(file, "", std::string("--set: ") + e.what());
  }
}

void ReadVersion(const JsonNode& root) {
  if (auto v = root.Optional("version")) {
    if (v->Integer() != 1) v->Fail("only version 1 is known, got " + std::to_string(v->Integer()));
  }
}

std::string OptionalString(const JsonNode& root, const char* key, const std::string& fallback) {
  auto v = root.Optional(key);
  return v ? v->String() : fallback;
}

}  // namespace cb::io::reading
