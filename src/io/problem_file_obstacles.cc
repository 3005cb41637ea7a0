#include "io/problem_file_obstacles.h"

#include <algorithm>

namespace cb::io::reading {

int Obstacles::Find(const JsonNode& ref) const {
  const std::string id = ref.String();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] == id) return static_cast<int>(k);
  }
  std::string known;
  for (const auto& i : ids) known += (known.empty() ? "" : ", ") + i;
  ref.Fail("unknown obstacle \"" + id + "\" (defined: " + (known.empty() ? "none" : known) + ")");
}

namespace {

// A curved obstacle's "side": "solid" (default) or "cavity".
Ball::Side ReadSide(const JsonNode& item) {
  Ball::Side side = Ball::Side::kSolid;
  if (auto s = item.Optional("side")) {
    const std::string text = s->String();
    if (text == "cavity") {
      side = Ball::Side::kCavity;
    } else if (text != "solid") {
      s->Fail("must be \"solid\" or \"cavity\", got \"" + text + "\"");
    }
  }
  return side;
}

}  // namespace

Obstacles ReadObstacles(const JsonNode& root, int dim) {
  Obstacles o;
  auto list = root.Optional("obstacles");
  if (!list) return o;
  for (const JsonNode& item : list->Items()) {
    const std::string type = item.Field("type").String();
    if (type == "half-space") {
      item.ExpectObject({"id", "type", "point", "normal"});
      const Point point = item.Field("point").Vector(dim);
      const Point normal = item.Field("normal").Vector(dim);
      if (!(normal.norm() > 0.0)) item.Field("normal").Fail("must not be the zero vector");
      o.list.push_back(std::make_shared<HalfSpace>(point, normal));
    } else if (type == "ball") {
      item.ExpectObject({"id", "type", "centre", "radius", "side"});
      const Point centre = item.Field("centre").Vector(dim);
      const double radius = item.Field("radius").Positive();
      o.list.push_back(std::make_shared<Ball>(centre, radius, ReadSide(item)));
    } else if (type == "cylinder" && dim == 3) {
      item.ExpectObject({"id", "type", "point", "axis", "radius", "side"});
      const Point point = item.Field("point").Vector(3);
      const Point axis = item.Field("axis").Vector(3);
      if (!(axis.norm() > 0.0)) item.Field("axis").Fail("must not be the zero vector");
      const double radius = item.Field("radius").Positive();
      o.list.push_back(std::make_shared<Cylinder>(point, axis, radius, ReadSide(item)));
    } else {
      item.Field("type").Fail(std::string("must be \"half-space\", \"ball\"") +
                              (dim == 3 ? " or \"cylinder\"" : "") + ", got \"" + type + "\"");
    }
    const JsonNode id = item.Field("id");
    const std::string text = id.String();
    if (text.empty()) id.Fail("must not be empty");
    if (std::find(o.ids.begin(), o.ids.end(), text) != o.ids.end()) {
      id.Fail("duplicate obstacle id \"" + text + "\"");
    }
    o.ids.push_back(text);
  }
  return o;
}

}  // namespace cb::io::reading
